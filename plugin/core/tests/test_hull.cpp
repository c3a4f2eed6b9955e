#include "acd/hull/hull.h"
#include "acd/mesh/measures.h"
#include "check.h"
#include "shapes.h"

#include <algorithm>
#include <random>

using namespace acd;

TEST_CASE("a box's hull has six facets, its volume and area")
{
	const TriMesh    b = shapes::box(Vec3(0, 0, 0), Vec3(2, 3, 4));
	const ConvexHull h(b.V);
	CHECK(h.facets() == 6);
	CHECK_NEAR(h.volume, 24.0, 1e-12);
	double area = 0;
	for (double a : h.facet_area) area += a;
	CHECK_NEAR(area, 2 * (6 + 8 + 12), 1e-12);
	for (const Plane& p : h.facet_plane)   // every corner on or below every facet plane
		for (const Vec3& v : b.V) CHECK(p.eval(v) <= 1e-12);
}

TEST_CASE("interior and repeated points do not change the hull")
{
	std::vector<Vec3> pts = shapes::box(Vec3(-1, -1, -1), Vec3(1, 1, 1)).V;
	pts.push_back(Vec3(0.2, -0.3, 0.1));
	pts.push_back(pts[0]);
	const ConvexHull h(pts);
	CHECK(h.points.size() == 8);
	CHECK(h.facets() == 6);
	for (size_t i = 0; i < h.points.size(); ++i) CHECK(pts[h.point_source[i]] == h.points[i]);
}

TEST_CASE("the canonical mesh depends on the points, not their order")
{
	std::vector<Vec3> pts = shapes::sphere(2, 1.0).V;
	const TriMesh     a   = ConvexHull(pts).canonical_mesh();
	std::shuffle(pts.begin(), pts.end(), std::mt19937(7));
	const TriMesh b = ConvexHull(pts).canonical_mesh();
	CHECK(a.V == b.V);
	CHECK(a.F == b.F);
	CHECK_NEAR(signed_volume(a), ConvexHull(pts).volume, 1e-12);
}

TEST_CASE("flat or too few points are refused")
{
	CHECK_THROWS_AS(ConvexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}), Error);
	CHECK_THROWS_AS(ConvexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(2, 3, 0)}), Error);
}

TEST_CASE("distance to the boundary of a cube")
{
	const ConvexHull h(shapes::box(Vec3(0, 0, 0), Vec3(2, 2, 2)).V);
	CHECK_NEAR(h.distance_to_boundary(Vec3(1, 1, 1)), 1.0, 1e-12);
	CHECK_NEAR(h.distance_to_boundary(Vec3(0.5, 1, 1)), 0.5, 1e-12);
	CHECK_NEAR(h.distance_to_boundary(Vec3(3, 1, 1)), 1.0, 1e-12);
}

