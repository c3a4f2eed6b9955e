#include "acd/hull/bounded_hull.h"
#include "acd/mesh/measures.h"
#include "check.h"
#include "shapes.h"

#include <algorithm>
#include <random>

using namespace acd;

namespace {
// Largest signed distance of the points outside the hull's facet planes (<= 0: all inside).
double outside(const std::vector<Vec3>& pts, const TriMesh& hull)
{
	double worst = -1e300;
	for (const Tri& t : hull.F) {
		const Vec3 n = (hull.V[t[1]] - hull.V[t[0]]).cross(hull.V[t[2]] - hull.V[t[0]]).normalized();
		for (const Vec3& p : pts) worst = std::max(worst, n.dot(p - hull.V[t[0]]));
	}
	return worst;
}
} // namespace

TEST_CASE("a hull within the budget comes back exact")
{
	const ConvexHull  h(shapes::box(Vec3(0, 0, 0), Vec3(2, 3, 4)).V);
	const BoundedHull b = bounded_hull(h, engine(Engine::PhysXGpu).budget, true);
	CHECK_FALSE(b.reduced);
	CHECK(b.reach == 0);
	CHECK(b.vertices == 8);
	CHECK(b.polygons == 6);
	CHECK(b.mesh.V.size() == 8);
	CHECK_NEAR(b.inscribed_radius, 1.0, 1e-9);
	CHECK_NEAR(b.extent, std::sqrt(29.0), 1e-12);
}

TEST_CASE("near-duplicate corners are welded when a budget is set, and the hull still holds them")
{
	// A box whose corners each carry a twin 1e-9 away, skewed so that the hull keeps sliver facets
	// between twins: an engine's cooking would merge the twins and count those facets its own way.
	std::vector<Vec3> pts = shapes::box(Vec3(0, 0, 0), Vec3(2, 3, 4)).V;
	for (size_t i = 0, n = pts.size(); i < n; ++i) pts.push_back(pts[i] + 1e-9 * Vec3(1, 0.7, 0.3 * i));
	const ConvexHull h(pts);
	CHECK(h.points.size() > 8);
	const BoundedHull none = bounded_hull(h, engine(Engine::None).budget);
	CHECK(none.mesh.V.size() == h.points.size());   // no budget: the exact hull, untouched
	const BoundedHull b = bounded_hull(h, engine(Engine::PhysX).budget);
	CHECK_FALSE(b.reduced);
	CHECK(b.mesh.V.size() == 8);
	for (size_t i = 0; i < b.mesh.V.size(); ++i)
		for (size_t j = i + 1; j < b.mesh.V.size(); ++j) CHECK((b.mesh.V[i] - b.mesh.V[j]).norm() > 1.0);
	CHECK(outside(pts, b.mesh) <= 1e-12);
	CHECK(b.reach > 0);
	CHECK(b.reach < 1e-7);
}

TEST_CASE("a plate thinner than the weld keeps its exact hull under a budget")
{
	for (double thick : {1e-9, 2e-7}) {   // flattened by the weld; kept 3-D but held only by scaling far out
		CAPTURE(thick);
		std::vector<Vec3> pts = shapes::box(Vec3(0, 0, 0), Vec3(2, 3, thick)).V;
		for (size_t i = 0, n = pts.size(); i < n; ++i) pts.push_back(pts[i] + Vec3(0.3e-6 * (i % 3), 0, 0));
		const ConvexHull  h(pts);
		const BoundedHull b = bounded_hull(h, engine(Engine::PhysX).budget);
		CHECK(b.within_budget);
		CHECK(outside(pts, b.mesh) <= 1e-12);
		CHECK(b.reach <= 1e-5);
		for (const Vec3& v : b.mesh.V) CHECK(v.norm() < 4.0);
	}
}

TEST_CASE("a reduced hull meets each engine's budget and still contains the exact hull")
{
	const std::vector<Vec3> sphere = shapes::sphere(4, 1.0).V;   // 2562 hull vertices
	const ConvexHull        h(sphere);
	for (Engine e : {Engine::PhysX, Engine::PhysXGpu, Engine::Unity}) {
		CAPTURE(engine(e).label);
		const HullBudget  budget = engine(e).budget;
		const BoundedHull b      = bounded_hull(h, budget, true);
		CHECK(b.reduced);
		CHECK(b.within_budget);
		const ConvexHull again(b.mesh.V);   // counted here, not read from the report
		if (budget.vertices) CHECK((int) again.points.size() <= budget.vertices);
		if (budget.polygons) CHECK(again.facets() <= budget.polygons);
		if (budget.triangles) CHECK((int) b.mesh.F.size() <= budget.triangles);
		CHECK(outside(sphere, b.mesh) <= 1e-12);   // rounding of this evaluation only
		// The reach is how far the reduced hull's corners stand off the sphere's hull (radius ~1).
		double far = 0;
		for (const Vec3& v : b.mesh.V) far = std::max(far, v.norm() - 1.0);
		CHECK(b.reach > 0);
		CHECK(b.reach <= far + 2e-3);
		CHECK(b.reach >= far - 2e-3);
		CHECK(b.reach < (e == Engine::PhysXGpu ? 0.2 : e == Engine::Unity ? 0.08 : 0.05));
		CHECK(b.inscribed_radius > 0.95);
	}
}

TEST_CASE("tiny budgets still contain: a tetrahedron at four vertices")
{
	const std::vector<Vec3> pts = shapes::sphere(2, 1.0).V;
	const BoundedHull       b   = bounded_hull(ConvexHull(pts), HullBudget{6, 0, 0, 0});
	CHECK(b.vertices <= 6);
	CHECK(b.vertices >= 4);
	CHECK(outside(pts, b.mesh) <= 1e-12);
}

TEST_CASE("the reduced hull depends on the points, not their order")
{
	std::vector<Vec3> pts = shapes::torus(1.0, 0.3, 40, 20).V;
	const TriMesh     a   = bounded_hull(ConvexHull(pts), engine(Engine::PhysXGpu).budget).mesh;
	std::shuffle(pts.begin(), pts.end(), std::mt19937(3));
	const TriMesh b = bounded_hull(ConvexHull(pts), engine(Engine::PhysXGpu).budget).mesh;
	CHECK(a.V == b.V);
	CHECK(a.F == b.F);
}

TEST_CASE("a thin plate's in-sphere is half its thickness")
{
	const ConvexHull h(shapes::box(Vec3(0, 0, 0), Vec3(100, 100, 0.5)).V);
	CHECK_NEAR(inscribed_radius(h), 0.25, 1e-9);
}
