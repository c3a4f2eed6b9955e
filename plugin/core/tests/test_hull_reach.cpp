#include "acd/decompose3/concavity.h"
#include "acd/decompose3/decompose.h"
#include "acd/hull/hull_reach.h"
#include "acd/solid/solid.h"
#include "shapes.h"
#include "check.h"

using namespace acd;

static ConcavityReport measure(const TriMesh& in, double tau = 0)
{
	Solid      s = make_solid(in);
	Topology   t(s.mesh);
	ConvexHull h(s.mesh.V);
	return measure_concavity(s.mesh, t, h, tau);
}

TEST_CASE("reach of an l prism is half its arm")
{
	// The bridge x + y = 3 stands 0.5 off the L's walls at its middle, (1.5, 1.5, z).
	const TriMesh     m = shapes::extrude(shapes::l_shape(), 0, 0.5);
	const ConvexHull  h(m.V);
	std::vector<char> all(h.facets(), 1);
	const HullReach   r = hull_reach(m, h, all, 0.0, 1e-4, 0.0);
	CHECK_NEAR(r.lower, 0.5, 1e-3);
	CHECK(r.upper <= 0.5 + 1e-4 + 1e-12);
	CHECK(r.upper >= r.lower);
	CHECK_NEAR(r.witness.x() + r.witness.y(), 3.0, 1e-3);   // at the bridge
	// The notch lies deeper than the bridge reaches: the paper's distance stays the concavity.
	const ConcavityReport c = measure(m);
	CHECK_NEAR(c.max_concavity, 1 / std::sqrt(2.0), 1e-12);
	CHECK(!c.reach_cut);
}

TEST_CASE("a low poly ring is as concave as its hole is wide")
{
	// A ring of square section (torus R 2, r 0.5, 4 segments across): its notches lie only 0.5 below
	// the hull's lid, but the lid spans the hole, 1.55 from the surface at the axis.
	const ConcavityReport c = measure(shapes::torus(2, 0.5, 16, 4));
	const double          expect = std::hypot(1.5 * std::cos(M_PI / 16), 0.5);
	CHECK_NEAR(c.hull_reach, expect, 0.01);   // refined to 1e-3 of the size (5) and 0.2%
	CHECK(c.max_concavity >= c.hull_reach);
	CHECK(c.reach_cut);
	CHECK((c.max_vertex >= 0 && c.max_bridge >= 0));
}

TEST_CASE("every leaf of a ring is certified")
{
	Solid            s = make_solid(shapes::torus(2, 0.5, 16, 4));
	DecomposeOptions o;
	o.tau = 0.6;   // above the notches' 0.5: only the hole's reach calls for cuts
	for (CutPlaneSelection sel : {CutPlaneSelection::Best, CutPlaneSelection::Bisector, CutPlaneSelection::MinSection,
	                               CutPlaneSelection::BisectorOrFace}) {
		o.cut_plane_selection = sel;
		const Decomposition d = decompose(s, o);
		CHECK(d.leaves().size() > 1);
		CHECK(d.tau_convex());
		for (int l : d.leaves()) {
			// Re-measured from scratch, every facet a candidate (no bridge classification trusted).
			const TriMesh&    m = d.nodes[l].mesh;
			const ConvexHull  h(m.V);
			std::vector<char> all(h.facets(), 1);
			CHECK(hull_reach(m, h, all, o.tau, 0.01 * o.tau, 0.0, 2000000).upper <= 1.01 * o.tau);
		}
	}
}

TEST_CASE("whether the reach is within floor + slack does not depend on the pose")
{
	// The L prism's reach is 0.5. Asked whether it is within 0.499 + 0.002, the search must settle
	// every bound below 0.501 even after it has met points beyond 0.499 (which of them it meets first
	// follows the pose); asked about 0.49 + 0.005, it must find a point beyond 0.495 in every pose.
	const TriMesh base = shapes::extrude(shapes::l_shape(), 0, 0.5);
	for (int k = 0; k < 8; ++k) {
		const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.37 * k, Vec3(1, 2, 3).normalized()) *
		                           Eigen::AngleAxisd(0.11 * k * k, Vec3(0, 1, 0)))
		                              .toRotationMatrix();
		TriMesh m = base;
		for (Vec3& v : m.V) v = R * v + Vec3(0.3 * k, -1.7, 2.1 * k);
		const ConvexHull  h(m.V);
		std::vector<char> all(h.facets(), 1);
		const HullReach   in = hull_reach(m, h, all, 0.499, 0.002, 0.02);
		CHECK(in.upper <= 0.501 + 1e-12);
		const HullReach out = hull_reach(m, h, all, 0.49, 0.005, 0.02);
		CHECK(out.lower > 0.495);
	}
}
