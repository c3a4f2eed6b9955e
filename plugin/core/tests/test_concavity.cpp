#include "acd/decompose3/concavity.h"
#include "acd/solid/solid.h"
#include "shapes.h"
#include "check.h"

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
