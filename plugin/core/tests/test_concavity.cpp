#include "acd/decompose3/concavity.h"
#include "acd/solid/solid.h"
#include "shapes.h"
#include "check.h"
#include "bench/obj_io.h"

using namespace acd;

static ConcavityReport measure(const TriMesh& in)
{
	Solid      s = make_solid(in);
	Topology   t(s.mesh);
	ConvexHull h(s.mesh.V);
	return measure_concavity(s.mesh, t, h);
}

TEST_CASE("convex shapes have no notch")
{
	for (const TriMesh& m : {shapes::box({0, 0, 0}, {1, 2, 3}), shapes::sphere(3, 1.0)}) {
		ConcavityReport r = measure(m);
		CHECK(r.notches == 0);
		CHECK(r.max_concavity == 0);
		CHECK(r.bridges == 0);
	}
}

TEST_CASE("l shape concavity is distance to its bridge")
{
	ConcavityReport r = measure(shapes::extrude(shapes::l_shape(), 0, 0.5));
	// The reflex corner (1,1) lies 1/sqrt(2) from the bridge x + y = 3.
	CHECK_NEAR(r.max_concavity, 1 / std::sqrt(2.0), 1e-12);
	CHECK(r.notches == 1);
	// The diagonal facet, and the top and bottom facets that the L covers only in part.
	CHECK(r.bridges == 3);
}

TEST_CASE("u shape concavity is its depth")
{
	// The U's notch (1,1) and (2,1) lie 1 below the bridge y = 2.
	ConcavityReport r = measure(shapes::extrude(shapes::u_shape(), 0, 1));
	CHECK_NEAR(r.max_concavity, 1.0, 1e-12);
	CHECK(r.notches == 2);
}

// Cut outlines put nearly collinear points on hulls; the sliver triangles between them have
// rounding-noise normals. Every facet plane must still bound the hull (a bogus plane made
// points deep inside look outside, and bridges far away look near).
TEST_CASE("hull facets bound the hull despite slivers")
{
	std::vector<acd::Vec3> pts;
	for (double z : {0.0, 1.0}) {
		pts.emplace_back(0, -1, z);
		pts.emplace_back(1, -1, z);
		pts.emplace_back(0, 0, z);
		pts.emplace_back(1, 0, z);
		for (int i = 1; i < 40; ++i) {   // bulging out of the face y = 0 by ~1e-15: strictly convex, barely
			const double t = i / 40.0;
			pts.emplace_back(t, 4e-15 * t * (1 - t), z);
		}
	}
	acd::ConvexHull h(pts);
	double worst = 0;
	for (int f = 0; f < h.facets(); ++f)
		for (const acd::Vec3& p : pts) worst = std::max(worst, h.facet_plane[f].eval(p));
	CHECK(worst < 1e-9);
}

TEST_CASE("a CAD part flat only to single precision measures the same when its coordinates are rounded again")
{
	// A part cut from a robot link exported in single precision: its -x side is a fan of hull facets
	// tilted by about 1e-6 against each other. Turned and turned back, its points move by about 1e-15,
	// which adds hull vertices on that side and small hull triangles between the tilted planes. A facet
	// grows against its first triangle's plane, not from neighbour to neighbour, or those small
	// triangles would join planes that rounding alone does not, and the bridges and concavity change.
	const TriMesh part = bench::read_obj(ACD_TEST_DATA "/cad_part_flat_to_float.obj");
	REQUIRE(part.V.size() == 910);
	const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.9, Vec3(0.3, -1, 2).normalized())).toRotationMatrix();
	TriMesh again = part;
	for (Vec3& p : again.V) p = R.transpose() * (R * p);
	double moved = 0;
	for (size_t v = 0; v < part.V.size(); ++v) moved = std::max(moved, (again.V[v] - part.V[v]).norm());
	CHECK(moved > 0);
	CHECK(moved < 1e-14);
	const Solid      a = make_solid(part), b = make_solid(again);
	const ConvexHull ha(a.mesh.V), hb(b.mesh.V);
	CHECK(ha.points.size() != hb.points.size());   // the rounding does reach the hull
	CHECK(ha.facets() == hb.facets());
	const ConcavityReport ra = measure_concavity(a.mesh, Topology(a.mesh), ha, 0.001);
	const ConcavityReport rb = measure_concavity(b.mesh, Topology(b.mesh), hb, 0.001);
	CHECK(ra.bridges == rb.bridges);
	CHECK(ra.patches == rb.patches);
	CHECK(ra.max_concavity == doctest::Approx(rb.max_concavity).epsilon(1e-9));
	// Measured here: the most concave notch lies at least that far inside its bridge's plane.
	const Plane& pa = ha.facet_plane[ra.max_bridge];
	CHECK(ra.max_concavity >= pa.d - pa.n.dot(a.mesh.V[ra.max_vertex]) - 1e-12);
}
