#include "acd/hull/bounded_hull.h"

#include <CGAL/Gmpzf.h>
#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <map>
#include <optional>
#include <set>

namespace acd {

HullBudget HullBudget::tighter(const HullBudget& o) const
{
	auto min0 = [](int a, int b) { return a == 0 ? b : b == 0 ? a : std::min(a, b); };
	return {min0(vertices, o.vertices), min0(polygons, o.polygons), min0(triangles, o.triangles),
	        min0(polygon_vertices, o.polygon_vertices)};
}

const std::vector<EngineRow>& engines()
{
	// Limits from the engines' documentation: PhysX cooks at most 255 vertices and 255 polygons, its GPU
	// path 64 vertices with at most 32 per polygon and refuses a hull whose in-sphere is over 100x smaller
	// than its largest extent; Unity's convex mesh colliders hold 255 triangles; MuJoCo and PyBullet take
	// any hull (MuJoCo collides each mesh geom as its hull, PyBullet one convex shape per OBJ object).
	static const std::vector<EngineRow> table = {
		{"none", Engine::None, "exact hulls", {}, 0},
		{"mujoco", Engine::MuJoCo, "exact hulls, one mesh geom each", {}, 0},
		{"pybullet", Engine::PyBullet, "exact hulls, one OBJ object each", {}, 0},
		{"physx", Engine::PhysX, "at most 255 vertices and 255 polygons per hull", {255, 255, 0, 0}, 0},
		{"physx_gpu", Engine::PhysXGpu,
		 "at most 64 vertices, 64 polygons and 32 corners per polygon; hulls thinner than 1/100 of their extent "
		 "are reported (PhysX runs them on the CPU)",
		 {64, 64, 0, 32}, 100},
		{"unity", Engine::Unity, "at most 255 triangles per hull", {0, 0, 255, 0}, 0},
	};
	return table;
}

const EngineRow& engine(Engine e)
{
	for (const EngineRow& r : engines())
		if (r.id == e) return r;
	return engines().front();
}

namespace {

struct Counts
{
	int vertices, polygons, triangles, polygon_vertices;
};

Counts count(const ConvexHull& h)
{
	int most = 0;
	for (const auto& tris : h.facet_triangles) {
		std::set<int> corners;
		for (int t : tris) corners.insert(h.triangles[t].begin(), h.triangles[t].end());
		most = std::max(most, (int) corners.size());
	}
	return {(int) h.points.size(), h.facets(), (int) h.triangles.size(), most};
}

bool fits(const Counts& c, const HullBudget& b)
{
	auto ok = [](int n, int limit) { return limit == 0 || n <= limit; };
	return ok(c.vertices, b.vertices) && ok(c.polygons, b.polygons) && ok(c.triangles, b.triangles) &&
	       ok(c.polygon_vertices, b.polygon_vertices);
}

// The vertex where planes i, j, k of `planes` meet.
Vec3 meet(const std::vector<Plane>& planes, int i, int j, int k)
{
	Eigen::Matrix3d A;
	A << planes[i].n.transpose(), planes[j].n.transpose(), planes[k].n.transpose();
	return A.fullPivLu().solve(Vec3(planes[i].d, planes[j].d, planes[k].d));
}

// The intersection of the half-spaces n.x <= d (bounded, holding c strictly inside), through its dual:
// plane j is the point n / (d - n.c), and each facet of their hull is a vertex, where the facet's planes
// meet. The vertex is solved from the facet's best-conditioned three planes, picked by plane index, so
// that it does not depend on the order CGAL hands the facets out.
ConvexHull intersect(const std::vector<Plane>& planes, const Vec3& c)
{
	std::vector<Vec3> dual;
	for (const Plane& p : planes) dual.push_back(p.n / (p.d - p.n.dot(c)));
	const ConvexHull  polar(dual);
	std::vector<Vec3> corners;
	for (const auto& tris : polar.facet_triangles) {
		std::set<int> ids;
		for (int t : tris)
			for (int v : polar.triangles[t]) ids.insert(polar.point_source[v]);
		const std::vector<int> p(ids.begin(), ids.end());
		std::array<int, 3>     best{p[0], p[1], p[2]};
		double                 det = -1;
		for (size_t a = 0; a < p.size(); ++a)
			for (size_t b = a + 1; b < p.size(); ++b)
				for (size_t e = b + 1; e < p.size(); ++e) {
					const double d = std::abs(planes[p[a]].n.dot(planes[p[b]].n.cross(planes[p[e]].n)));
					if (d > det) std::tie(det, best) = std::make_tuple(d, std::array<int, 3>{p[a], p[b], p[e]});
				}
		corners.push_back(meet(planes, best[0], best[1], best[2]));
	}
	// In sorted order: a polygon with more than three corners is triangulated the same way every run.
	std::sort(corners.begin(), corners.end(), [](const Vec3& a, const Vec3& b) {
		return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
	});
	return ConvexHull(corners);
}

// Four support planes of a tetrahedron around the points, in their principal frame.
std::vector<Plane> enclosing_tetrahedron(const std::vector<Vec3>& P, const Vec3& c)
{
	Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
	for (const Vec3& p : P) C += (p - c) * (p - c).transpose();
	const Eigen::Matrix3d E = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C).eigenvectors();
	std::vector<Plane> out;
	for (const Vec3 s : {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)}) {
		Plane pl;
		pl.n = (E * s).normalized();
		pl.d = -1e300;
		for (const Vec3& p : P) pl.d = std::max(pl.d, pl.n.dot(p));
		out.push_back(pl);
	}
	return out;
}

BoundedHull result(const ConvexHull& h, const ConvexHull& exact, bool reduced, const HullBudget& budget)
{
	BoundedHull b;
	b.mesh                                                        = h.mesh();
	const Counts c                                                = count(h);
	std::tie(b.vertices, b.polygons, b.triangles, b.polygon_vertices) = std::tie(c.vertices, c.polygons, c.triangles, c.polygon_vertices);
	b.reduced       = reduced;
	b.within_budget = fits(c, budget);
	if (&h != &exact)   // any other hull may reach beyond the exact one
		for (const Vec3& v : b.mesh.V) {
			double out = -1;
			for (const Plane& f : exact.facet_plane) out = std::max(out, f.eval(v));
			if (out > 0) b.reach = std::max(b.reach, exact.distance_to_boundary(v));
		}
	return b;
}

// The in-sphere's radius and the largest distance between two vertices: what an engine's thinness test reads.
void measure(BoundedHull& b, const ConvexHull& h)
{
	b.inscribed_radius = inscribed_radius(h);
	for (size_t i = 0; i < b.mesh.V.size(); ++i)
		for (size_t j = i + 1; j < b.mesh.V.size(); ++j) b.extent = std::max(b.extent, (b.mesh.V[i] - b.mesh.V[j]).norm());
}

// The exact hull's facet planes, each computed from its corners in sorted order and sorted by value, so
// that the planes picked depend on the hull's shape alone.
std::vector<Plane> sorted_planes(const ConvexHull& h, const Vec3& c)
{
	std::vector<Plane> planes;
	for (const auto& tris : h.facet_triangles) {
		std::set<std::array<double, 3>> ids;
		for (int t : tris)
			for (int v : h.triangles[t]) ids.insert({h.points[v].x(), h.points[v].y(), h.points[v].z()});
		std::vector<Vec3> q;
		for (const auto& a : ids) q.emplace_back(a[0], a[1], a[2]);
		// The first corner, the one farthest from it, and the one farthest from their line.
		auto far = [&](auto dist) { return *std::max_element(q.begin(), q.end(), [&](const Vec3& a, const Vec3& b) { return dist(a) < dist(b); }); };
		const Vec3 a = q[0], b = far([&](const Vec3& p) { return (p - a).squaredNorm(); });
		const Vec3 e = far([&](const Vec3& p) { return (p - a).cross(b - a).squaredNorm(); });
		Plane      pl;
		pl.n = (b - a).cross(e - a).normalized();
		if (pl.n.dot(a - c) < 0) pl.n = -pl.n;
		pl.d = -1e300;
		for (const Vec3& p : q) pl.d = std::max(pl.d, pl.n.dot(p));
		planes.push_back(pl);
	}
	std::sort(planes.begin(), planes.end(), [](const Plane& a, const Plane& b) {
		return std::make_tuple(a.n.x(), a.n.y(), a.n.z(), a.d) < std::make_tuple(b.n.x(), b.n.y(), b.n.z(), b.d);
	});
	return planes;
}

// Corners closer than `tol` made one (the first in sorted order): planes that nearly meet in a point give
// clusters of corners and sliver facets that an engine's own hull would count differently.
ConvexHull weld_corners(const ConvexHull& h, double tol)
{
	std::vector<Vec3> kept;
	for (const Vec3& v : h.points)
		if (std::none_of(kept.begin(), kept.end(), [&](const Vec3& k) { return (k - v).norm() <= tol; })) kept.push_back(v);
	return ConvexHull(kept);
}

// Whether two of the points lie within `tol` of each other (swept along x).
bool clustered(std::vector<Vec3> P, double tol)
{
	std::sort(P.begin(), P.end(), [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); });
	for (size_t i = 0; i < P.size(); ++i)
		for (size_t j = i + 1; j < P.size() && P[j].x() - P[i].x() <= tol; ++j)
			if ((P[j] - P[i]).norm() <= tol) return true;
	return false;
}

// How far the points of P stand outside the hull's triangles, as a share of each triangle plane's distance
// from c (<= 0: all inside). Each triangle's own plane, as an engine or Qhull sees the hull: a merged
// facet's fitted plane can pass a few rounding steps beside its triangles.
double outside_share(const ConvexHull& h, const std::vector<Vec3>& P, const Vec3& c)
{
	const TriMesh m     = h.mesh();
	double        share = 0;
	for (const Tri& t : m.F) {
		const Vec3 n = (m.V[t[1]] - m.V[t[0]]).cross(m.V[t[2]] - m.V[t[0]]).normalized();
		if (!n.allFinite()) continue;
		const double d    = std::max({n.dot(m.V[t[0]]), n.dot(m.V[t[1]]), n.dot(m.V[t[2]])});
		const double room = d - n.dot(c);
		if (!(room > 0)) continue;
		for (const Vec3& p : P) share = std::max(share, (n.dot(p) - d) / room);
	}
	return share;
}

// The vertices solved from the planes carry rounding: a point of P may lie a few ulps outside. Scaled
// about c just enough that every point of P is inside (a change of the order of that rounding); `holds`
// says whether three rounds of it got there.
struct Held
{
	ConvexHull hull;
	bool       holds;
};
Held hold(ConvexHull h, const std::vector<Vec3>& P, const Vec3& c)
{
	for (int round = 0;; ++round) {
		const double grow = outside_share(h, P, c);
		if (grow <= 0 || round == 3) return {std::move(h), grow <= 0};
		std::vector<Vec3> V = h.points;   // sorted, as in intersect()
		for (Vec3& v : V) v = c + (v - c) * (1 + 2 * grow + 1e-15);
		h = ConvexHull(V);
	}
}

// Welded at `tol`, then held around P; none when the weld leaves no volume (a part thinner than `tol`).
std::optional<Held> weld_and_hold(const ConvexHull& h, const std::vector<Vec3>& P, const Vec3& c, double tol)
{
	try {
		return hold(weld_corners(h, tol), P, c);
	} catch (const Error&) {
		return std::nullopt;
	}
}

// A reduced hull as it is handed out: welded and held when that holds, else held as solved.
Held finish(ConvexHull h, const std::vector<Vec3>& P, const Vec3& c, double size)
{
	std::optional<Held> welded = weld_and_hold(h, P, c, 1e-6 * size);
	if (welded && welded->holds) return std::move(*welded);
	return hold(std::move(h), P, c);
}

} // namespace

BoundedHull bounded_hull(const ConvexHull& exact, const HullBudget& budget, bool measure_inscribed)
{
	const bool fits_exact = fits(count(exact), budget);
	if (fits_exact && !budget.limited()) {
		BoundedHull b = result(exact, exact, false, budget);
		if (measure_inscribed) measure(b, exact);
		return b;
	}
	const std::vector<Vec3>  P      = exact.points;
	Vec3                     c      = Vec3::Zero();
	for (const Vec3& p : P) c += p;
	c /= (double) P.size();
	double size = 0;
	for (const Vec3& p : P) size = std::max(size, (p - c).norm());
	// An engine cooks its own hull from the vertices and merges near-duplicate corners its own way: the
	// sliver facets between them count differently there. Welded (and held) first, the count is the same.
	if (fits_exact) {
		// A part thinner than the weld (a plate of rounding's thickness) would be flattened, or scaled far
		// beyond itself to hold its points: its exact hull is kept as it is.
		const std::optional<Held> clean = weld_and_hold(exact, P, c, 1e-6 * size);
		BoundedHull b  = clean ? result(clean->hull, exact, false, budget) : BoundedHull{};
		// Corners closer than the weld would be welded by an engine, which then counts the slivers between
		// them as polygons of their own: such a hull is welded whenever its weld holds the points near
		// the part (1e-3 of its size: a plate thinner than the weld is held only far out).
		const double near = clustered(exact.points, 1e-6 * size) ? 1e-3 : 1e-5;
		const bool   ok   = clean && clean->holds && b.within_budget && b.reach <= near * size;
		if (!ok) b = result(exact, exact, false, budget);
		if (measure_inscribed) measure(b, ok ? clean->hull : exact);
		return b;
	}
	const std::vector<Plane> facets = sorted_planes(exact, c);
	std::vector<Plane>       kept   = enclosing_tetrahedron(P, c);
	ConvexHull               best   = intersect(kept, c);
	// Each vertex's worst facet, remembered: a new plane changes only a few vertices.
	std::map<std::array<double, 3>, std::pair<double, int>> worst;
	for (size_t step = 0; step < facets.size(); ++step) {
		double far = 1e-9 * size;
		int    pick = -1;
		for (const Vec3& v : best.points) {
			auto [it, fresh] = worst.try_emplace({v.x(), v.y(), v.z()}, -1e300, -1);
			if (fresh)
				for (int f = 0; f < (int) facets.size(); ++f)
					if (facets[f].eval(v) > it->second.first) it->second = {facets[f].eval(v), f};
			if (it->second.first > far) std::tie(far, pick) = it->second;
		}
		if (pick < 0) break;   // within rounding of the exact hull
		kept.push_back(facets[pick]);
		ConvexHull next = intersect(kept, c);
		if (!fits(count(next), budget)) break;
		best = std::move(next);
	}
	// A weld moves corners off their polygons' planes and can split a polygon in two: the planes added
	// last are given back until the finished hull fits (the first four always do).
	Held done = finish(std::move(best), P, c, size);
	while (!fits(count(done.hull), budget) && kept.size() > 4) {
		kept.pop_back();
		done = finish(intersect(kept, c), P, c, size);
	}
	BoundedHull b = result(done.hull, exact, true, budget);
	if (measure_inscribed) measure(b, done.hull);
	return b;
}

double inscribed_radius(const ConvexHull& hull)
{
	// max r subject to n.x + r <= d for every facet: x free, r >= 0 (centred for conditioning).
	Vec3 c = Vec3::Zero();
	for (const Vec3& p : hull.points) c += p;
	c /= (double) hull.points.size();
	CGAL::Quadratic_program<double> lp(CGAL::SMALLER, false, 0, false, 0);
	for (int i = 0; i < hull.facets(); ++i) {
		const Plane& f = hull.facet_plane[i];
		for (int k = 0; k < 3; ++k) lp.set_a(k, i, f.n[k]);
		lp.set_a(3, i, 1.0);
		lp.set_b(i, f.d - f.n.dot(c));
	}
	lp.set_l(3, true, 0.0);
	lp.set_c(3, -1.0);
	const auto s = CGAL::solve_linear_program(lp, CGAL::Gmpzf());
	return s.is_optimal() ? -CGAL::to_double(s.objective_value()) : 0.0;
}

} // namespace acd
