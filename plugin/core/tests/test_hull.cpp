#include "acd/hull/hull.h"
#include "acd/hull/hull_traits.h"
#include "acd/mesh/measures.h"
#include "check.h"
#include "shapes.h"

#include <algorithm>
#include <array>
#include <random>
#include <set>

#include <CGAL/convex_hull_3.h>

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

TEST_CASE("the hull's mesh depends on the points, not their order")
{
	std::vector<Vec3> pts = shapes::sphere(2, 1.0).V;
	const TriMesh     a   = ConvexHull(pts).mesh();
	std::shuffle(pts.begin(), pts.end(), std::mt19937(7));
	const TriMesh b = ConvexHull(pts).mesh();
	CHECK(a.V == b.V);
	CHECK(a.F == b.F);
	CHECK_NEAR(signed_volume(a), ConvexHull(pts).volume, 1e-12);
}

TEST_CASE("the facets depend on the points, not on the order CGAL hands its triangles out")
{
	// A box with points along its edges lifted by a few rounding steps: sliver triangles along every edge,
	// which join a facet by the order of their neighbours. Shuffled input reorders CGAL's triangles.
	std::mt19937                           rng(3);
	std::uniform_real_distribution<double> u(-1, 1);
	std::vector<Vec3>                      pts = shapes::box(Vec3(-1, -1, -1), Vec3(1, 1, 1)).V;
	for (int e = 0; e < 12; ++e)
		for (int k = 0; k < 6; ++k) {
			const int ax = e / 4;
			Vec3      p;
			p[ax]            = u(rng);
			p[(ax + 1) % 3] = (e & 1 ? 1 : -1) * (1 + 1e-13 * std::abs(u(rng)));
			p[(ax + 2) % 3] = (e & 2 ? 1 : -1) * (1 + 1e-13 * std::abs(u(rng)));
			pts.push_back(p);
		}
	using Corners = std::set<std::array<double, 3>>;
	auto facets   = [](const ConvexHull& h) {   // each facet as the set of its corners
		std::set<Corners> out;
		for (const auto& tris : h.facet_triangles) {
			Corners c;
			for (int t : tris)
				for (int v : h.triangles[t]) c.insert({h.points[v].x(), h.points[v].y(), h.points[v].z()});
			out.insert(c);
		}
		return out;
	};
	const ConvexHull first(pts);
	CHECK(first.facets() == 6);
	for (int s = 0; s < 10; ++s) {
		CAPTURE(s);
		std::shuffle(pts.begin(), pts.end(), std::mt19937(s));
		const ConvexHull again(pts);
		CHECK(facets(again) == facets(first));
		CHECK(again.points == first.points);
		CHECK(again.triangles == first.triangles);
	}
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


TEST_CASE("the hull traits give CGAL's default hull on points coplanar to rounding")
{
	// Points on the faces of a turned cube: coplanar only to rounding, so nearly every test of a point
	// against a facet falls through the filters to exact arithmetic.
	using K = CGAL::Exact_predicates_inexact_constructions_kernel;
	const Eigen::Matrix3d turn = (Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized())).toRotationMatrix();
	std::mt19937          rng(7);
	std::uniform_real_distribution<double> u(-1, 1);
	std::vector<K::Point_3>                pts;
	for (int i = 0; i < 3000; ++i) {
		Vec3 p(u(rng), u(rng), u(rng));
		p[i % 3] = i % 2 ? 1 : -1;
		p        = turn * p;
		pts.emplace_back(p.x(), p.y(), p.z());
	}
	CGAL::Surface_mesh<K::Point_3> a, b;
	CGAL::convex_hull_3(pts.begin(), pts.end(), a);
	CGAL::convex_hull_3(pts.begin(), pts.end(), b, HullTraits());
	const auto faces = [](const CGAL::Surface_mesh<K::Point_3>& m) {
		std::vector<std::array<std::array<double, 3>, 3>> f;
		for (auto fi : m.faces()) {
			std::array<std::array<double, 3>, 3> t;
			int k = 0;
			for (auto v : CGAL::vertices_around_face(m.halfedge(fi), m)) t[k++] = {m.point(v).x(), m.point(v).y(), m.point(v).z()};
			std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
			f.push_back(t);
		}
		std::sort(f.begin(), f.end());
		return f;
	};
	CHECK(a.number_of_vertices() > 8);   // the rounding leaves points beyond the cube's corners
	CHECK(faces(a) == faces(b));
}
