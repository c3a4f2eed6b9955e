#include "acd/prepare/plane_fill.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

namespace acd {

namespace {

using K   = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb  = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fbi = CGAL::Triangulation_face_base_with_info_2<int, K>;   // nesting depth: odd inside the polygon
using Fb  = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Constraints that cross are no simple polygon: refused, not split.
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;

// Faces of one plane agree in their normals to within this angle (radians), besides lying within eps.
constexpr double kAngle = 1e-3;
// Three planes meet at one corner only if their normals' triple product is at least this.
constexpr double kCorner = 1e-2;
// A rim on more distinct planes than this is left to the fairing (their ways to meet grow as the
// Catalan numbers: 132 for 8).
constexpr int kMostPlanes = 8;
// A single edge of the rim on a plane of its own joins a stretch beside it whose plane holds its ends
// within this share of its length (absorb_single_edges).
constexpr double kNearlyOn = 0.2;

// For each rim edge, the rim edge that follows it (its `to` the other's `from`); empty if that is not
// one edge. Where the rim passes a vertex twice (two openings that touch at a vertex between two fans of
// faces), the edge arriving along one fan's end leaves along the other fan's: the border edge met
// turning about the vertex through the arriving edge's own fan (across the faces' shared edges)
// borders the other opening. The fans are found among the faces `about` (empty: all of m's).
std::vector<size_t> following(const TriMesh& m, const std::vector<RimEdge>& rim, const std::vector<int>& about)
{
	std::map<int, std::vector<size_t>> leaving;
	for (size_t i = 0; i < rim.size(); ++i) leaving[rim[i].from].push_back(i);
	std::set<int> pinched;
	for (const auto& [v, out] : leaving)
		if (out.size() > 1) pinched.insert(v);
	std::map<std::pair<int, int>, int> face_of;   // the edges into a pinch, by the face that runs them
	const auto note = [&](int f) {
		for (int k = 0; k < 3; ++k)
			if (pinched.count(m.F[f][k])) face_of[{m.F[f][(k + 2) % 3], m.F[f][k]}] = f;
	};
	if (!pinched.empty()) {
		if (about.empty())
			for (int f = 0; f < (int) m.F.size(); ++f) note(f);
		for (int f : about) note(f);
	}
	const auto own_way_out = [&](const RimEdge& in) {   // the target of the fan's border edge out of in.to
		int f = in.face;
		for (size_t turns = 0; turns <= face_of.size(); ++turns) {
			const Tri& t = m.F[f];
			const long k = std::find(t.begin(), t.end(), in.to) - t.begin();
			if (k == 3) return -1;
			const auto g = face_of.find({t[(k + 1) % 3], in.to});
			if (g == face_of.end()) return t[(k + 1) % 3];
			f = g->second;
		}
		return -1;
	};
	std::vector<size_t> next(rim.size());
	for (size_t i = 0; i < rim.size(); ++i) {
		const auto it = leaving.find(rim[i].to);
		if (it == leaving.end() || it->second.size() > 2) return {};
		const std::vector<size_t>& out = it->second;
		const int z = out.size() == 1 ? -1 : own_way_out(rim[i]);
		if (out.size() == 2 && rim[out[0]].to != z && rim[out[1]].to != z) return {};
		next[i] = out.size() == 1 || rim[out[1]].to == z ? out[0] : out[1];
	}
	return next;
}

// The rim as simple cycles in the order `following` gives; empty if it is no such thing.
std::vector<std::vector<RimEdge>> cycles_of(const TriMesh& m, const std::vector<RimEdge>& rim, const std::vector<int>& about)
{
	const std::vector<size_t> next = following(m, rim, about);
	if (next.empty()) return {};
	std::vector<std::vector<RimEdge>> cycles;
	std::vector<char>                 used(rim.size(), 0);
	for (size_t s = 0; s < rim.size(); ++s) {
		if (used[s]) continue;
		std::vector<RimEdge> c;
		std::set<int>        seen;
		for (size_t i = s; !used[i]; i = next[i]) {
			if (!seen.insert(rim[i].from).second) return {};   // still not simple
			used[i] = 1;
			c.push_back(rim[i]);
		}
		if (c.back().to != c.front().from) return {};
		cycles.push_back(std::move(c));
	}
	return cycles;
}

std::optional<Vec3> unit_normal(const TriMesh& m, int f)
{
	const Vec3 n = (m.V[m.F[f][1]] - m.V[m.F[f][0]]).cross(m.V[m.F[f][2]] - m.V[m.F[f][0]]);
	if (!(n.norm() > 0)) return std::nullopt;
	return n.normalized();
}

// Face f lies on plane pl: its corners within eps and its normal within kAngle.
bool on_plane(const TriMesh& m, int f, const Plane& pl, double eps)
{
	const std::optional<Vec3> n = unit_normal(m, f);
	return n && pl.holds(m.V, m.F[f], eps) && n->dot(pl.n) >= std::cos(kAngle);
}

struct Run
{
	size_t first, count;   // edges of the cycle
	int    plane;
};

// An edge of the rim along a crease has its face on one plane and the missing face on the other: it
// belongs to the stretch of the other plane, so that each plane's patch ends on the crease.
void settle_creases(const TriMesh& m, const std::vector<RimEdge>& c, double eps, std::vector<Run>& runs, const std::vector<Plane>& planes)
{
	const size_t n = c.size(), R = runs.size();
	// edge e (its face on plane `own`) lies on plane p as well
	const auto on = [&](size_t e, int own, int p) {
		return on_plane(m, c[e % n].face, planes[own], eps) && std::abs(planes[p].eval(m.V[c[e % n].from])) <= eps &&
		       std::abs(planes[p].eval(m.V[c[e % n].to])) <= eps;
	};
	for (size_t r = 0; R > 1 && r < R; ++r) {
		Run &a = runs[r], &b = runs[(r + 1) % R];
		while (a.count > 1 && on(a.first + a.count - 1, a.plane, b.plane)) --a.count, ++b.count, b.first = (b.first + n - 1) % n;
		while (b.count > 1 && on(b.first, b.plane, a.plane)) ++a.count, --b.count, b.first = (b.first + 1) % n;
	}
}

// A jagged rim across a faceted curve (a cylinder's or a cone's narrow facets) may cross a facet along a
// single edge between two stretches of several: such an edge joins the one beside it whose plane holds
// both its ends within kNearlyOn of its length (the facets turn by a few degrees), so that the facets
// about it meet as that stretch's plane continued. (A rim of single edges, as on a finely faceted
// sphere, keeps them: it is faired.) Stretches that end up side by side on one plane become one;
// planes no stretch keeps are dropped.
void absorb_single_edges(const TriMesh& m, const std::vector<RimEdge>& c, std::vector<Run>& runs, std::vector<Plane>& planes)
{
	for (size_t r = 0; r < runs.size();) {
		const size_t R = runs.size(), before = (r + R - 1) % R, after = (r + 1) % R;
		if (R <= 2 || runs[r].count != 1 || runs[before].count < 2 || runs[after].count < 2) {
			++r;
			continue;
		}
		const RimEdge& e     = c[runs[r].first % c.size()];
		const double   tol   = kNearlyOn * (m.V[e.to] - m.V[e.from]).norm();
		const auto     holds = [&](const Run& o) {
            return std::abs(planes[o.plane].eval(m.V[e.from])) <= tol && std::abs(planes[o.plane].eval(m.V[e.to])) <= tol;
		};
		const bool to_before = holds(runs[before]);
		if (!to_before && !holds(runs[after])) {
			++r;
			continue;
		}
		if (to_before) ++runs[before].count;
		else runs[after].first = runs[r].first, ++runs[after].count;
		std::vector<size_t> gone{r};
		if (runs[before].plane == runs[after].plane) {   // one stretch now, through the edge
			runs[before].count += runs[after].count;
			gone.push_back(after);
		}
		std::sort(gone.rbegin(), gone.rend());
		for (size_t g : gone) runs.erase(runs.begin() + (long) g);
		r = 0;
	}
	std::vector<int>   id(planes.size(), -1);
	std::vector<Plane> kept;
	for (Run& run : runs) {
		if (id[run.plane] < 0) id[run.plane] = (int) kept.size(), kept.push_back(planes[run.plane]);
		run.plane = id[run.plane];
	}
	planes = std::move(kept);
}

// The cycle (rotated to start where a stretch starts) cut into stretches on one plane each, and the
// distinct planes; false if a face has no normal or a stretch is a single edge.
bool stretches(const TriMesh& m, std::vector<RimEdge>& c, double eps, std::vector<Run>& runs, std::vector<Plane>& planes)
{
	const size_t n = c.size();
	std::vector<Plane> own(n);
	for (size_t i = 0; i < n; ++i) {
		const std::optional<Vec3> nf = unit_normal(m, c[i].face);
		if (!nf) return false;
		own[i] = through(m.V[c[i].from], *nf);
	}
	size_t start = 0;
	while (start < n && on_plane(m, c[start].face, own[(start + n - 1) % n], eps)) ++start;
	if (start == n) start = 0;   // the whole rim on one plane
	std::rotate(c.begin(), c.begin() + start, c.end());
	std::rotate(own.begin(), own.begin() + start, own.end());
	for (size_t i = 0; i < n; ++i) {
		if (!runs.empty() && on_plane(m, c[i].face, planes[runs.back().plane], eps)) {
			++runs.back().count;
			continue;
		}
		int p = 0;
		while (p < (int) planes.size() && !on_plane(m, c[i].face, planes[p], eps)) ++p;
		if (p == (int) planes.size()) planes.push_back(own[i]);
		runs.push_back({i, 1, p});
	}
	absorb_single_edges(m, c, runs, planes);
	if (!std::all_of(runs.begin(), runs.end(), [](const Run& r) { return r.count >= 2; })) return false;
	settle_creases(m, c, eps, runs, planes);
	return true;
}

// Where planes a, b, c meet, if they meet at one point.
std::optional<Vec3> corner_of(const Plane& a, const Plane& b, const Plane& c)
{
	Eigen::Matrix3d A;
	A.row(0) = a.n.transpose(), A.row(1) = b.n.transpose(), A.row(2) = c.n.transpose();
	if (!(std::abs(A.determinant()) >= kCorner)) return std::nullopt;
	return Vec3(A.partialPivLu().solve(Vec3(a.d, b.d, c.d)));
}

// Near the hole: within 1.5 times the rim's radius of its centroid (the same in any pose).
struct Ball
{
	Vec3   centre = Vec3::Zero();
	double radius = 0;
	Ball(const TriMesh& m, const std::vector<RimEdge>& c)
	{
		for (const RimEdge& e : c) centre += m.V[e.from];
		centre /= (double) c.size();
		for (const RimEdge& e : c) radius = std::max(radius, (m.V[e.from] - centre).norm());
	}
	bool holds(const Vec3& q) const { return (q - centre).norm() <= 1.5 * radius; }
};

// The patch's polygons being built: each plane's vertices in rim order, the corners made so far.
struct Polygons
{
	std::vector<std::vector<int>>  of;        // per plane: vertex ids (>= 0 surface, < 0 corner)
	std::vector<Vec3>              corners;
	std::map<std::array<int, 3>, int> corner_id;   // the planes that meet there, sorted
};

// Where a patch's vertex id lies: the surface's vertex v (>= 0), or corner -1 - v.
const Vec3& point_of(const TriMesh& m, const std::vector<Vec3>& corners, int v) { return v >= 0 ? m.V[v] : corners[-1 - v]; }

// A stretch's rim vertices appended to its plane's polygon: each edge's start, then the last one's end.
void append_stretch(const std::vector<RimEdge>& c, const Run& run, std::vector<int>& poly)
{
	for (size_t e = 0; e < run.count; ++e) poly.push_back(c[(run.first + e) % c.size()].from);
	poly.push_back(c[(run.first + run.count - 1) % c.size()].to);
}

// Each plane's polygon: its stretches in rim order, each joined to the next one on the plane along the
// crease with the plane the rim turns to there (the same at both ends), or through the corner of the
// plane with the two planes the rim visits in between; false where neither holds.
bool polygons(const std::vector<RimEdge>& c, const std::vector<Run>& runs, const std::vector<Plane>& planes,
              const Ball& near, Polygons& out)
{
	const size_t R = runs.size();
	out.of.assign(planes.size(), {});
	for (size_t r = 0; r < R; ++r) {
		const int P = runs[r].plane;
		std::vector<int>& poly = out.of[P];
		append_stretch(c, runs[r], poly);
		std::set<int> between;
		size_t        s = (r + 1) % R;
		for (; runs[s].plane != P; s = (s + 1) % R) between.insert(runs[s].plane);
		if (between.empty()) {   // the next stretch on P starts where this one ends
			poly.pop_back();
			continue;
		}
		const int X = runs[(r + 1) % R].plane, Y = runs[(s + R - 1) % R].plane;
		if (X == Y) continue;
		if (between.size() != 2) return false;
		std::array<int, 3> key{P, X, Y};
		std::sort(key.begin(), key.end());
		auto it = out.corner_id.find(key);
		if (it == out.corner_id.end()) {
			const std::optional<Vec3> q = corner_of(planes[P], planes[X], planes[Y]);
			if (!q || !near.holds(*q)) return false;
			it = out.corner_id.emplace(key, -1 - (int) out.corners.size()).first;
			out.corners.push_back(*q);
		}
		poly.push_back(it->second);
	}
	return true;
}

// The polygon's points in the plane's own 2D frame, the same in any pose: from its first point, along its
// first edge, snapped to a grid of a power of two (about 1e-8 of its extent). Points on a regular grid
// (cocircular quadruples, which the Delaunay triangulation settles by their coordinates) then tie alike
// in every pose, and the patch is triangulated alike. (Only the triangulation's connectivity is kept:
// the patch's vertices stay where they are.)
std::vector<Eigen::Vector2d> plane_coordinates(const std::vector<Vec3>& at, const Plane& pl, bool snap = true)
{
	Vec3 e1 = pl.n.unitOrthogonal();
	for (size_t i = 1; i < at.size(); ++i) {
		const Vec3 d = at[i] - at[0] - pl.n * pl.n.dot(at[i] - at[0]);
		if (d.norm() > 0) {
			e1 = d.normalized();
			break;
		}
	}
	const Vec3                   e2 = pl.n.cross(e1);
	std::vector<Eigen::Vector2d> q;
	double                       extent = 0;
	for (const Vec3& p : at) {
		q.emplace_back((p - at[0]).dot(e1), (p - at[0]).dot(e2));
		extent = std::max(extent, q.back().cwiseAbs().maxCoeff());
	}
	// The grid is shifted by a share of a step that no binary fraction comes near: coordinates written
	// with few bits (float exports, round CAD sizes) fall on halves of a power-of-two grid, where the
	// rounding noise of a pose would decide which way they snap.
	const double step = std::ldexp(1.0, std::ilogb(std::max(extent, 1e-300)) - 26), shift = 0.3183098861837907;
	if (snap)
		for (Eigen::Vector2d& p : q) p = ((p / step).array() + shift).round().matrix() * step;
	return q;
}

// The triangles of a simple polygon on plane pl that runs clockwise about pl.n (as a rim runs about
// its hole), each counterclockwise about pl.n; false if it is not such a polygon. The polygon may touch
// itself at a vertex it lists twice (split_creases). `snap`: in plane_coordinates' snapped frame, or,
// where two of its points fall within one grid step, unsnapped.
bool triangulate(const std::vector<int>& poly, const std::vector<Vec3>& at, const Plane& pl, std::vector<Tri>& out,
                 bool snap = true)
{
	std::vector<K::Point_2> pts;
	double area = 0;
	for (const Eigen::Vector2d& q : plane_coordinates(at, pl, snap)) pts.emplace_back(q.x(), q.y());
	for (size_t i = 0; i < pts.size(); ++i) {
		const K::Point_2 &a = pts[i], &b = pts[(i + 1) % pts.size()];
		area += a.x() * b.y() - b.x() * a.y();
	}
	if (!(area < 0)) return false;
	CDT cdt;
	try {
		std::vector<CDT::Vertex_handle> vh;
		for (size_t i = 0; i < pts.size(); ++i) vh.push_back(cdt.insert(pts[i])), vh.back()->info() = poly[i];
		for (size_t i = 0; i < vh.size(); ++i) cdt.insert_constraint(vh[i], vh[(i + 1) % vh.size()]);
	}
	catch (const std::exception&) {
		return false;
	}
	// A vertex may repeat where the polygon touches itself (split_creases); two at one point may not.
	const size_t distinct = std::set<int>(poly.begin(), poly.end()).size();
	if (cdt.number_of_vertices() != distinct)   // two points within a grid step (a corner at a rim vertex)
		return snap && triangulate(poly, at, pl, out, false);
	for (CDT::All_faces_iterator f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
	// Depth: constrained edges crossed from outside, flooded one depth at a time.
	std::vector<CDT::Face_handle> seeds{cdt.infinite_face()};
	for (int depth = 0; !seeds.empty(); ++depth) {
		std::vector<CDT::Face_handle> todo, next;
		for (CDT::Face_handle f : seeds)
			if (f->info() < 0) f->info() = depth, todo.push_back(f);
		for (size_t i = 0; i < todo.size(); ++i)
			for (int k = 0; k < 3; ++k) {
				const CDT::Face_handle g = todo[i]->neighbor(k);
				if (g->info() >= 0) continue;
				if (cdt.is_constrained({todo[i], k})) next.push_back(g);
				else g->info() = depth, todo.push_back(g);
			}
		seeds = std::move(next);
	}
	size_t made = 0;
	for (CDT::Finite_faces_iterator f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
		if (f->info() != 1) {
			if (f->info() > 1) return false;
			continue;
		}
		out.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}), ++made;
	}
	return made + 2 + 2 * (pts.size() - distinct) == pts.size();   // each touch parts off one more polygon
}

// Every patch edge is a rim edge run the other way (once) or met by the patch's own edge run the other
// way, and no edge is run twice: the patch closes the hole as one surface.
bool closes(const std::vector<RimEdge>& c, const std::vector<Tri>& faces)
{
	std::set<std::pair<int, int>> run, rim;
	for (const RimEdge& e : c) rim.insert({e.from, e.to});
	for (const Tri& t : faces)
		for (int k = 0; k < 3; ++k)
			if (!run.insert({t[k], t[(k + 1) % 3]}).second) return false;
	size_t met = 0;
	for (const auto& [a, b] : run) {
		if (rim.count({b, a})) ++met;
		else if (!run.count({b, a})) return false;
	}
	return met == rim.size();
}

// A jagged rim may touch a crease between two of its stretches (a vertex of the solid's edge, between
// two vertices off it): that vertex is put into every polygon edge that passes through it, so that the
// planes meeting at the crease split it alike. Such a polygon touches itself there.
void split_creases(const TriMesh& m, const std::vector<RimEdge>& c, const std::vector<Plane>& planes, double eps, Polygons& pg)
{
	std::set<std::pair<int, int>> rim;
	for (const RimEdge& e : c) rim.insert(std::minmax(e.from, e.to));
	const auto at = [&](int v) { return point_of(m, pg.corners, v); };
	for (size_t p = 0; p < pg.of.size(); ++p) {
		const std::vector<int>& poly = pg.of[p];
		std::vector<int>        out;
		for (size_t i = 0; i < poly.size(); ++i) {
			const int a = poly[i], b = poly[(i + 1) % poly.size()];
			out.push_back(a);
			if (rim.count(std::minmax(a, b))) continue;
			const Vec3   A = at(a), d = at(b) - A;
			const double len2 = d.squaredNorm();
			std::vector<std::pair<double, int>> on;
			for (const RimEdge& e : c) {
				const double t = len2 > 0 ? (m.V[e.from] - A).dot(d) / len2 : 0;
				if (e.from != a && e.from != b && t > 0 && t < 1 && (A + t * d - m.V[e.from]).norm() <= eps &&
				    std::abs(planes[p].eval(m.V[e.from])) <= eps)
					on.emplace_back(t, e.from);
			}
			std::sort(on.begin(), on.end());
			for (const auto& tw : on) out.push_back(tw.second);
		}
		pg.of[p] = std::move(out);
	}
}

// The polygons triangulated, if each is simple (or touches itself at a vertex) and they close the hole
// together.
std::optional<PlanePatch> patch_of(const TriMesh& m, const std::vector<RimEdge>& c, const std::vector<Plane>& planes, Polygons pg,
                                   double eps)
{
	split_creases(m, c, planes, eps, pg);
	PlanePatch out;
	out.corners = pg.corners;
	for (size_t p = 0; p < planes.size(); ++p) {
		std::vector<Vec3> at;
		for (int v : pg.of[p]) at.push_back(point_of(m, pg.corners, v));
		if (!triangulate(pg.of[p], at, planes[p], out.faces)) return std::nullopt;
	}
	if (!closes(c, out.faces)) return std::nullopt;
	return out;
}

using Triangles = std::vector<std::array<int, 3>>;

// Every triangulation of the polygon of vertices lo..hi (in a fixed order).
std::vector<Triangles> triangulations(int lo, int hi)
{
	if (hi - lo < 2) return {Triangles{}};
	std::vector<Triangles> all;
	for (int a = lo + 1; a < hi; ++a)
		for (const Triangles& left : triangulations(lo, a))
			for (const Triangles& right : triangulations(a, hi)) {
				Triangles t = left;
				t.insert(t.end(), right.begin(), right.end());
				t.push_back({lo, a, hi});
				all.push_back(std::move(t));
			}
	return all;
}

// Stretches on as many planes as there are stretches are a polygon whose vertices are the planes: each
// triangulation of it is a way for the planes to meet inside the hole (a triangle, the corner where its
// three planes meet; a diagonal, the crease of its two). Each stretch's polygon follows it, then the
// corners of its triangles in turn about it. The way that makes valid polygons of least area is kept.
std::optional<PlanePatch> corner_tree(const TriMesh& m, const std::vector<RimEdge>& c, const std::vector<Run>& runs,
                                      const std::vector<Plane>& planes, const Ball& near, double eps)
{
	const int k = (int) runs.size();
	if (k > kMostPlanes) return std::nullopt;
	std::optional<PlanePatch> best;
	double                    least = 0;
	for (const Triangles& tri : triangulations(0, k - 1)) {
		Polygons pg;
		pg.of.assign(planes.size(), {});
		bool ok = true;
		for (const std::array<int, 3>& t : tri) {
			const std::optional<Vec3> q = corner_of(planes[runs[t[0]].plane], planes[runs[t[1]].plane], planes[runs[t[2]].plane]);
			ok = ok && q && near.holds(*q);
			if (ok) pg.corners.push_back(*q);
		}
		for (int r = 0; ok && r < k; ++r) {
			std::vector<int>& poly = pg.of[runs[r].plane];
			append_stretch(c, runs[r], poly);
			std::vector<std::pair<int, int>> fan;   // (the nearer other vertex's offset after r, corner)
			for (size_t i = 0; i < tri.size(); ++i) {
				const std::array<int, 3>& t = tri[i];
				if (t[0] != r && t[1] != r && t[2] != r) continue;
				int offset = k;
				for (int x : t)
					if (x != r) offset = std::min(offset, (x - r + k) % k);
				fan.emplace_back(offset, -1 - (int) i);
			}
			std::sort(fan.begin(), fan.end());
			for (const auto& [offset, corner] : fan) poly.push_back(corner);
		}
		std::optional<PlanePatch> p = ok ? patch_of(m, c, planes, pg, eps) : std::nullopt;
		if (!p) continue;
		double area = 0;
		const auto at = [&](int v) { return point_of(m, p->corners, v); };
		for (const Tri& f : p->faces) area += (at(f[1]) - at(f[0])).cross(at(f[2]) - at(f[0])).norm();
		if (!best || area < least) best = std::move(p), least = area;
	}
	return best;
}

// One simple cycle of the rim closed on its planes.
std::optional<PlanePatch> cycle_patch(const TriMesh& m, std::vector<RimEdge>& c, double eps)
{
	std::vector<Run>   runs;
	std::vector<Plane> planes;
	if (c.size() < 3 || !stretches(m, c, eps, runs, planes)) return std::nullopt;
	const Ball near(m, c);
	if (runs.size() >= 3 && planes.size() == runs.size()) return corner_tree(m, c, runs, planes, near, eps);
	Polygons pg;
	if (!polygons(c, runs, planes, near, pg)) return std::nullopt;
	return patch_of(m, c, planes, pg, eps);
}

} // namespace

std::optional<PlanePatch> plane_patch(const TriMesh& m, const std::vector<RimEdge>& rim, double eps, const std::vector<int>& about)
{
	PlanePatch out;
	const std::vector<std::vector<RimEdge>> cycles = cycles_of(m, rim, about);
	if (cycles.empty()) return std::nullopt;
	for (std::vector<RimEdge> c : cycles) {   // each closed on its own; the corners numbered on
		std::optional<PlanePatch> p = cycle_patch(m, c, eps);
		if (!p) return std::nullopt;
		const int shift = (int) out.corners.size();
		out.corners.insert(out.corners.end(), p->corners.begin(), p->corners.end());
		for (Tri t : p->faces) {
			for (int& v : t)
				if (v < 0) v -= shift;
			out.faces.push_back(t);
		}
	}
	return out;
}

} // namespace acd
