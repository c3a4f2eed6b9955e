// make_solid's edge checks and the crossing search, against CGAL's own search of the whole soup.
#include "check.h"
#include "shapes.h"
#include "acd/mesh/measures.h"
#include "acd/solid/solid.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <doctest/doctest.h>

#include <algorithm>

using namespace acd;

namespace {

// Every crossing face pair by one CGAL search of the whole mesh, as (smaller, larger), sorted.
std::vector<std::pair<int, int>> all_crossings(const TriMesh& m)
{
	using K = CGAL::Exact_predicates_inexact_constructions_kernel;
	std::vector<K::Point_3> pts;
	for (const Vec3& p : m.V) pts.emplace_back(p.x(), p.y(), p.z());
	std::vector<std::array<std::size_t, 3>> tris;
	for (const Tri& t : m.F) tris.push_back({(std::size_t) t[0], (std::size_t) t[1], (std::size_t) t[2]});
	std::vector<std::pair<std::size_t, std::size_t>> pairs;
	CGAL::Polygon_mesh_processing::triangle_soup_self_intersections(pts, tris, std::back_inserter(pairs));
	std::vector<std::pair<int, int>> out;
	for (const auto& [f, g] : pairs) out.push_back({(int) std::min(f, g), (int) std::max(f, g)});
	std::sort(out.begin(), out.end());
	return out;
}

TriMesh moved(TriMesh m, const Vec3& by)
{
	for (Vec3& p : m.V) p += by;
	return m;
}

std::pair<Error::Code, long> error_of(const TriMesh& m)
{
	try {
		make_solid(m);
	}
	catch (const Error& e) {
		return {e.code, e.count};
	}
	return {Error::Unspecified, -1L};
}

} // namespace

TEST_CASE("bad input is refused with a reason")
{
	TriMesh open = shapes::box({0, 0, 0}, {1, 1, 1});
	open.F.pop_back();
	auto refused = [](const TriMesh& m, const std::string& word) {
		try {
			make_solid(m);
		}
		catch (const Error& e) {
			return e.kind == Error::InvalidInput && std::string(e.what()).find(word) != std::string::npos;
		}
		return false;
	};
	CHECK(refused(open, "boundary edges"));
	CHECK(refused(TriMesh{}, "empty"));
	CHECK(refused(TriMesh{{Vec3(0, 0, 0), Vec3(1, 0, 0)}, {}}, "point cloud"));
	CHECK(make_solid(shapes::inverted(shapes::box({0, 0, 0}, {1, 1, 1}))).flipped);
	CHECK_NEAR(make_solid(shapes::inverted(shapes::box({0, 0, 0}, {1, 1, 1}))).volume, 1.0, 1e-12);
	TriMesh nan = shapes::box({0, 0, 0}, {1, 1, 1});
	nan.V[0].x() = std::nan("");
	CHECK(refused(nan, "NaN"));
}

TEST_CASE("input errors carry their code and count for the host's repair")
{
	TriMesh open = shapes::box({0, 0, 0}, {1, 1, 1});
	open.F.pop_back();
	CHECK(error_of(open) == std::make_pair(Error::OpenMesh, 3L));
	TriMesh dup = shapes::box({0, 0, 0}, {1, 1, 1});
	dup.F.push_back(dup.F[0]);
	dup.F.push_back(dup.F[1]);
	CHECK(error_of(dup) == std::make_pair(Error::DuplicateFaces, 2L));
	TriMesh flipped = shapes::box({0, 0, 0}, {1, 1, 1});
	std::swap(flipped.F[0][1], flipped.F[0][2]);
	CHECK(error_of(flipped).first == Error::Misoriented);
	CHECK(error_of(TriMesh{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {}}) == std::make_pair(Error::PointCloud, 3L));
	TriMesh repeated = shapes::box({0, 0, 0}, {1, 1, 1});
	repeated.F[0][1] = repeated.F[0][0];
	CHECK(error_of(repeated).first == Error::RepeatedVertex);
	for (const TriMesh& m : {open, dup, flipped}) {   // the core's words name no host's repair
		try {
			make_solid(m);
		}
		catch (const Error& e) {
			CHECK(std::string(e.what()).find("meshing_") == std::string::npos);
		}
	}
}

TEST_CASE("the crossings of a large mesh, searched in slabs, are exactly those of one search")
{
	// Two spheres of 82k faces each overlapping along a circle (and, turned, along a tilted one): the
	// search splits them into slabs along the longest axis, and pairs near slab borders must be found once.
	for (const Vec3& offset : {Vec3(1.1, 0, 0), Vec3(0.3, 0.9, 0.4)}) {
		const TriMesh m = shapes::merge(shapes::sphere(6, 1.0), moved(shapes::sphere(6, 1.0), offset));
		REQUIRE(m.F.size() > 150000);
		const std::vector<std::pair<int, int>> expected = all_crossings(m);
		REQUIRE(expected.size() > 500);
		CHECK(self_crossings(m, bbox_diagonal(m.V)) == expected);
		const Solid s = make_solid(m);
		CHECK(s.self_intersections == (long) expected.size());
		CHECK(s.shells == 2);
	}
	// Apart, nothing crosses.
	const TriMesh apart = shapes::merge(shapes::sphere(6, 1.0), moved(shapes::sphere(6, 1.0), Vec3(2.5, 0, 0)));
	CHECK(self_crossings(apart, bbox_diagonal(apart.V)).empty());
}

TEST_CASE("edges used by more than two faces are counted once per edge, whichever way they run")
{
	// Three tetrahedra on one edge: it is used six times.
	TriMesh fins;
	fins.V = {Vec3(0, 0, 0), Vec3(0, 0, 1)};
	for (int k = 0; k < 3; ++k) {
		const double a = 2 * M_PI * k / 3;
		const int    base = (int) fins.V.size();
		fins.V.push_back(Vec3(std::cos(a), std::sin(a), 0.5));
		fins.V.push_back(Vec3(std::cos(a + 0.5), std::sin(a + 0.5), 0.5));
		const TriMesh tet{{fins.V[0], fins.V[1], fins.V[base], fins.V[base + 1]}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};
		const double  v   = signed_volume(tet);
		for (Tri t : tet.F) {
			for (int& i : t) i = i < 2 ? i : base + i - 2;
			if (v < 0) std::swap(t[1], t[2]);
			fins.F.push_back(t);
		}
	}
	CHECK(error_of(fins) == std::make_pair(Error::NonManifoldEdges, 1L));
	// The faces on that edge all turned to run it from 1 to 0: still one non-manifold edge (not
	// reported as a misoriented one).
	TriMesh one_way = fins;
	for (Tri& t : one_way.F)
		if (std::count(t.begin(), t.end(), 0) && std::count(t.begin(), t.end(), 1)) {
			const int i1 = (int) (std::find(t.begin(), t.end(), 1) - t.begin());
			if (t[(i1 + 1) % 3] != 0) std::swap(t[1], t[2]);
		}
	CHECK(error_of(one_way).first == Error::NonManifoldEdges);
}

TEST_CASE("boxes meeting at a corner are one solid with that vertex split")
{
	const TriMesh a = shapes::box({0, 0, 0}, {1, 1, 1});
	TriMesh       b = shapes::box({1, 1, 1}, {2, 2, 2});
	TriMesh       m = a;
	for (const Tri& t : b.F) {
		Tri u = t;
		for (int& i : u) {
			const auto same = std::find(a.V.begin(), a.V.end(), b.V[i]);
			i = same != a.V.end() ? (int) (same - a.V.begin()) : (int) (a.V.size() + i);
		}
		m.F.push_back(u);
	}
	m.V.insert(m.V.end(), b.V.begin(), b.V.end());
	const Solid s = make_solid(m);
	CHECK(s.split_vertices == 1);
	CHECK(s.shells == 2);
	CHECK(s.volume == doctest::Approx(2.0));
	CHECK(s.self_intersections == 0);
}

TEST_CASE("a solid of one shell made without the crossing search says so; several shells are searched anyway")
{
	const TriMesh one = shapes::sphere(3, 1.0);
	const Solid   s   = make_solid(one, false);
	CHECK(s.self_intersections == -1);
	CHECK(s.crossing_faces.empty());
	CHECK(s.shells == 1);
	CHECK(s.volume == doctest::Approx(make_solid(one).volume));
	// Two spheres crossing: their nesting needs the crossings, so they are found.
	const TriMesh two = shapes::merge(shapes::sphere(3, 1.0), moved(shapes::sphere(3, 1.0), Vec3(1.1, 0, 0)));
	const Solid   t   = make_solid(two, false);
	CHECK(t.shells == 2);
	CHECK(t.self_intersections == (long) all_crossings(two).size());
	CHECK(t.self_intersections > 0);
}
