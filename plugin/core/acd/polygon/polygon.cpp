#include "acd/polygon/polygon.h"
#include "acd/mesh/parallel.h"
#include "acd/recursion/recursion.h"
#include "acd/mesh/measures.h"
#include "acd/recursion/hole_order.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <map>
#include <queue>
#include <set>
#include <sstream>

namespace acd {

// The recursion's hole count of a polygon node.
int holes_in(const Node2& n)
{
	return n.hole_count;
}

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

[[noreturn]] void invalid(const std::string& m) { throw Error(Error::InvalidInput, m); }

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Twice the largest distance from the points' centroid: a size that does not change with pose.
double extent2(const Loop2& pts)
{
	Vec2 c = Vec2::Zero();
	for (const Vec2& p : pts) c += p;
	c /= (double) pts.size();
	double r = 0;
	for (const Vec2& p : pts) r = std::max(r, (p - c).norm());
	return 2 * r;
}

// Segments of all loops cross or touch anywhere but at shared loop corners? Sweep by x with exact
// predicates (CGAL's filtered kernel).
bool loops_cross(const std::vector<Loop2>& loops)
{
	struct Seg
	{
		K::Segment_2 s;
		int          loop, i;
		double       lo, hi;
	};
	std::vector<Seg> segs;
	for (int l = 0; l < (int) loops.size(); ++l)
		for (int i = 0; i < (int) loops[l].size(); ++i) {
			const Vec2 &a = loops[l][i], &b = loops[l][(i + 1) % loops[l].size()];
			segs.push_back({K::Segment_2(K::Point_2(a.x(), a.y()), K::Point_2(b.x(), b.y())), l, i,
			                std::min(a.x(), b.x()), std::max(a.x(), b.x())});
		}
	std::sort(segs.begin(), segs.end(), [](const Seg& a, const Seg& b) { return a.lo < b.lo; });
	for (size_t i = 0; i < segs.size(); ++i)
		for (size_t j = i + 1; j < segs.size() && segs[j].lo <= segs[i].hi; ++j) {
			const Seg &a = segs[i], &b = segs[j];
			if (a.loop == b.loop) {
				const int n = (int) loops[a.loop].size();
				const bool ab = (a.i + 1) % n == b.i, ba = (b.i + 1) % n == a.i;
				if (ab || ba) {
					// Neighbours share corner m; they overlap only if they fold back onto each other.
					const Seg& s1 = ab ? a : b;
					const Seg& s2 = ab ? b : a;
					const auto &p = s1.s.source(), &m = s1.s.target(), &q = s2.s.target();
					if (CGAL::orientation(p, m, q) == CGAL::COLLINEAR && CGAL::angle(p, m, q) == CGAL::ACUTE) return true;
					if (n > 3 || !(ab && ba)) continue;
				}
			}
			if (CGAL::do_intersect(a.s, b.s)) return true;
		}
	return false;
}

Loop2 cleaned(const Loop2& in, double tol)
{
	Loop2 out;
	for (const Vec2& p : in)
		if (out.empty() || (p - out.back()).norm() > tol) out.push_back(p);
	while (out.size() > 1 && (out.front() - out.back()).norm() <= tol) out.pop_back();
	return out;
}

} // namespace

std::vector<Polygon2> polygons_from_loops(std::vector<Loop2> loops)
{
	if (loops.empty()) invalid("The polygon has no boundary loop.");
	Loop2 all;
	for (const Loop2& l : loops)
		for (const Vec2& p : l) {
			if (!p.allFinite()) invalid("The polygon has NaN or infinite coordinates.");
			all.push_back(p);
		}
	if (all.size() < 3) invalid("The polygon has fewer than 3 points.");
	const double size = extent2(all);
	if (!(size > 0)) invalid("The polygon is degenerate: all its points coincide.");
	for (Loop2& l : loops) {
		l = cleaned(l, 1e-12 * size);
		if (l.size() < 3) invalid("A boundary loop has fewer than 3 distinct points.");
	}
	if (loops_cross(loops))
		invalid("The boundary loops cross or touch themselves or each other; a polygon's outer boundary and "
		        "holes must be simple and disjoint.");
	for (const Loop2& l : loops)
		if (!(std::abs(signed_area(l)) > 1e-14 * size * size)) invalid("A boundary loop encloses no area.");

	// Nesting by point in polygon (loops do not cross, so one point of a loop decides).
	const int           n = (int) loops.size();
	std::vector<int>    depth(n, 0), parent(n, -1);
	std::vector<double> a(n);
	for (int i = 0; i < n; ++i) a[i] = std::abs(signed_area(loops[i]));
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j)
			if (i != j && inside(loops[j], loops[i][0])) {
				++depth[i];
				if (parent[i] < 0 || a[j] < a[parent[i]]) parent[i] = j;
			}
	std::vector<Polygon2> out;
	std::vector<int>      index(n, -1);
	for (int i = 0; i < n; ++i)
		if (depth[i] % 2 == 0) {
			if (signed_area(loops[i]) < 0) std::reverse(loops[i].begin(), loops[i].end());
			index[i] = (int) out.size();
			out.push_back({loops[i], {}});
		}
	for (int i = 0; i < n; ++i)
		if (depth[i] % 2 == 1) {
			if (signed_area(loops[i]) > 0) std::reverse(loops[i].begin(), loops[i].end());
			out[index[parent[i]]].holes.push_back(loops[i]);
		}
	// Largest first, as the 3D solids.
	std::stable_sort(out.begin(), out.end(), [](const Polygon2& x, const Polygon2& y) { return area(x) > area(y); });
	return out;
}

Concavity2 measure_concavity(const Polygon2& p)
{
	const Loop2& P = p.outer;
	const int    n = (int) P.size();
	Concavity2   r;
	r.outer.assign(n, 0.0);
	const double flat = 1e-9 * extent2(P);

	// Convex hull of the outer loop (Andrew's monotone chain, strictly convex corners), as indices.
	std::vector<int> idx(n);
	std::iota(idx.begin(), idx.end(), 0);
	std::sort(idx.begin(), idx.end(), [&](int i, int j) {
		return P[i].x() < P[j].x() || (P[i].x() == P[j].x() && P[i].y() < P[j].y());
	});
	auto turn = [&](int o, int a, int b) {
		return CGAL::orientation(K::Point_2(P[o].x(), P[o].y()), K::Point_2(P[a].x(), P[a].y()),
		                         K::Point_2(P[b].x(), P[b].y()));
	};
	std::vector<int> hull(2 * n);
	int              k = 0;
	for (int i = 0; i < n; ++i) {
		while (k >= 2 && turn(hull[k - 2], hull[k - 1], idx[i]) != CGAL::LEFT_TURN) --k;
		hull[k++] = idx[i];
	}
	for (int i = n - 2, t = k + 1; i >= 0; --i) {
		while (k >= t && turn(hull[k - 2], hull[k - 1], idx[i]) != CGAL::LEFT_TURN) --k;
		hull[k++] = idx[i];
	}
	hull.resize(k - 1);   // counter-clockwise, like the outer loop

	// Bridges: consecutive hull vertices that are not consecutive on the boundary; the vertices
	// between them form the pocket, measured to the bridge's line (Algorithm 5.1).
	const int h = (int) hull.size();
	for (int i = 0; i < h; ++i) {
		const int a = hull[i], b = hull[(i + 1) % h];
		if ((b - a + n) % n <= 1) continue;
		++r.bridges;
		const Vec2 e = (P[b] - P[a]).normalized();
		for (int v = (a + 1) % n; v != b; v = (v + 1) % n) r.outer[v] = std::max(0.0, cross(e, P[v] - P[a]));
	}
	for (int v = 0; v < n; ++v) {
		const Vec2 &prev = P[(v + n - 1) % n], &cur = P[v], &next = P[(v + 1) % n];
		const Vec2  chord = next - prev;
		// reflex: the corner lies clearly left of its neighbours' chord (inside a counter-clockwise loop)
		if (chord.norm() > 0 && cross(chord.normalized(), cur - prev) > flat) {
			++r.notches;
			if (r.outer[v] > r.max_concavity || r.max_vertex < 0) {
				r.max_concavity = r.outer[v];
				r.max_vertex    = v;
			}
		}
	}
	// A hole's depth: its deepest vertex's distance to the hull's boundary.
	for (const Loop2& H : p.holes) {
		double deepest = 0;
		for (const Vec2& q : H) {
			double d = HUGE_VAL;
			for (int i = 0; i < h; ++i) {
				const Vec2& a = P[hull[i]];
				d = std::min(d, cross((P[hull[(i + 1) % h]] - a).normalized(), q - a));
			}
			deepest = std::max(deepest, d);
		}
		r.hole_depth.push_back(deepest);
	}
	return r;
}

namespace {

struct Crossing
{
	int    loop, edge;   // loop 0 = outer, 1 + i = hole i; edge from vertex `edge` to the next
	double t;            // along the line from the anchor
	Vec2   x;
	int    vertex = -1;  // the cut ends exactly at this outer vertex (a notch-to-vertex cut)
};

const Loop2& loop_of(const Polygon2& p, int l) { return l == 0 ? p.outer : p.holes[l - 1]; }

// The cut: segments (pairs of crossings, or the notch vertex and a crossing) splitting `p`; then
// the boundaries are walked into loops, turning onto the cut at each of its ends.
// `on` > 0 lets the cut from a notch end exactly at an outer vertex lying on the line (within
// `on`): a cut from notch to notch; any other vertex on the line makes it fail (the caller nudges).
// Where the line from `from` along `dir` crosses the loops, sorted along it; with `on` > 0, loop
// vertices within `on` of the line count as crossings at the vertex. False if the line runs through
// a hole's vertex ahead.
bool line_crossings(const Polygon2& p, const Vec2& from, int vertex, const Vec2& dir, double on,
                    std::vector<Crossing>& xs)
{
	const int nl = 1 + (int) p.holes.size();
	for (int l = 0; l < nl; ++l) {
		const Loop2& L = loop_of(p, l);
		const int    n = (int) L.size();
		for (int i = 0; i < n; ++i) {
			if (on > 0 && !(l == 0 && i == vertex) && std::abs(cross(dir, L[i] - from)) <= on) {
				const double t = dir.dot(L[i] - from);
				if (l != 0 && t > 0) return false;
				if (l == 0 && t > 0) xs.push_back({0, i, t, L[i], i});
			}
		}
		for (int i = 0; i < n; ++i) {
			const int j = (i + 1) % n;
			if (l == 0 && (i == vertex || j == vertex)) continue;   // the notch's own edges
			const double si = cross(dir, L[i] - from), sj = cross(dir, L[j] - from);
			if (on > 0 && (std::abs(si) <= on || std::abs(sj) <= on)) continue;   // met at a vertex
			if ((si > 0) == (sj > 0)) continue;
			const Vec2 x = L[i] + si / (si - sj) * (L[j] - L[i]);
			xs.push_back({l, i, dir.dot(x - from), x});
		}
	}
	std::sort(xs.begin(), xs.end(), [](const Crossing& a, const Crossing& b) { return a.t < b.t; });
	return true;
}

// The stretch of the line to cut: from the notch (or the last outer crossing before the anchor) to
// the first outer crossing after it; to each hole met, then on from that hole's last crossing before
// the end (the paper's leftmost and rightmost edges of a hole): a hole crossed several times is
// entered once, and each segment joins two boundaries, so the last one splits the polygon in exactly
// two. Consecutive pairs of `cut` are the segments; false if they do not run inside the polygon.
bool cut_segments(const Polygon2& p, const std::vector<Crossing>& xs, int vertex, std::vector<Crossing>& cut)
{
	int first = -1, last = -1;
	for (int i = 0; i < (int) xs.size(); ++i)
		if (xs[i].t > 0 && xs[i].loop == 0) {
			last = i;
			break;
		}
	if (last < 0) return false;
	if (vertex < 0) {
		for (int i = last - 1; i >= 0; --i)
			if (xs[i].t < 0 && xs[i].loop == 0) {
				first = i;
				break;
			}
		if (first < 0) return false;
	}
	int i = 0;
	if (vertex >= 0) {
		cut.push_back({0, vertex, 0.0, p.outer[vertex]});
		while (i < last && xs[i].t <= 0) ++i;
	}
	else {
		cut.push_back(xs[first]);
		i = first + 1;
	}
	while (i < last) {
		const int l = xs[i].loop;
		int       j = last - 1;
		while (xs[j].loop != l) --j;
		cut.push_back(xs[i]);
		cut.push_back(xs[j]);
		i = j + 1;
	}
	cut.push_back(xs[last]);
	if (cut.size() % 2 != 0) return false;
	const double size = extent2(p.outer);
	for (size_t k = 0; k < cut.size(); k += 2) {
		const Vec2 mid = (cut[k].x + cut[k + 1].x) / 2;
		if ((cut[k + 1].x - cut[k].x).norm() < 1e-12 * size || !inside(p.outer, mid)) return false;
		for (const Loop2& H : p.holes)
			if (inside(H, mid)) return false;
	}
	return true;
}

// The boundary with the cut in it: nodes are every loop vertex, then the cut's crossing points (the
// notch is its own vertex); bnext follows the boundary, cnext the cut (-1 off it).
struct CutGraph
{
	std::vector<Vec2> pos;
	std::vector<int>  bnext, cnext;

	bool build(const Polygon2& p, int vertex, const std::vector<Crossing>& cut)
	{
		const int        nl = 1 + (int) p.holes.size();
		std::vector<int> base(nl + 1, 0);
		for (int l = 0; l < nl; ++l) base[l + 1] = base[l] + (int) loop_of(p, l).size();
		for (int l = 0; l < nl; ++l)
			for (const Vec2& q : loop_of(p, l)) pos.push_back(q);
		bnext.resize(base[nl]);
		for (int l = 0; l < nl; ++l)
			for (int i = base[l]; i < base[l + 1]; ++i) bnext[i] = i + 1 < base[l + 1] ? i + 1 : base[l];
		std::vector<int> node(cut.size());
		for (size_t i = 0; i < cut.size(); ++i) {
			if (vertex >= 0 && i == 0) {
				node[i] = base[0] + vertex;
				continue;
			}
			if (cut[i].vertex >= 0) {
				if (i + 1 != cut.size()) return false;   // only the cut's end may be a vertex
				node[i] = base[0] + cut[i].vertex;
				continue;
			}
			const int a = base[cut[i].loop] + cut[i].edge;
			node[i]     = (int) pos.size();
			pos.push_back(cut[i].x);
			bnext.push_back(bnext[a]);   // a -> crossing -> a's old next
			bnext[a] = node[i];
		}
		cnext.assign(pos.size(), -1);
		for (size_t i = 0; i < cut.size(); i += 2) {
			cnext[node[i]]     = node[i + 1];
			cnext[node[i + 1]] = node[i];
		}
		return true;
	}

	// Walk: after a boundary edge into a cut end, take the cut; after the cut, the boundary. False if
	// a walk does not close where it started.
	bool loops(std::vector<Loop2>& out) const
	{
		const int         nn = (int) pos.size();
		std::vector<char> done_b(nn, 0), done_c(nn, 0);
		for (int s = 0; s < nn; ++s) {
			if (done_b[s]) continue;
			Loop2 L;
			int   u       = s;
			bool  via_cut = false;   // the edge leaving u is a cut edge
			int   guard   = 0;
			while (true) {
				char& d = via_cut ? done_c[u] : done_b[u];
				if (d) break;
				d = 1;
				L.push_back(pos[u]);
				const int v = via_cut ? cnext[u] : bnext[u];
				via_cut     = !via_cut && cnext[v] >= 0;
				u           = v;
				if (++guard > 2 * nn + 4) return false;
			}
			if (u != s || via_cut) return false;
			out.push_back(std::move(L));
		}
		return true;
	}
};

// Two outer loops, and each hole inside one of them.
bool two_pieces(std::vector<Loop2>& loops, std::array<Polygon2, 2>& out)
{
	std::vector<Loop2> outers, holes;
	for (Loop2& L : loops) (signed_area(L) > 0 ? outers : holes).push_back(std::move(L));
	if (outers.size() != 2) return false;
	for (int i = 0; i < 2; ++i) out[i] = {outers[i], {}};
	for (Loop2& H : holes) {
		int host = inside(outers[0], H[0]) ? 0 : inside(outers[1], H[0]) ? 1 : -1;
		if (host < 0) return false;
		out[host].holes.push_back(std::move(H));
	}
	return true;
}

bool separate_at(const Polygon2& p, const Vec2& from, int vertex, const Vec2& dir, std::array<Polygon2, 2>& out,
                 Vec2* cut_from, Vec2* cut_to, double on = 0)
{
	std::vector<Crossing> xs, cut;
	CutGraph              g;
	std::vector<Loop2>    loops;
	if (!line_crossings(p, from, vertex, dir, on, xs) || !cut_segments(p, xs, vertex, cut) || !g.build(p, vertex, cut) ||
	    !g.loops(loops) || !two_pieces(loops, out))
		return false;
	if (cut_from) *cut_from = cut.front().x;
	if (cut_to) *cut_to = cut.back().x;
	return true;
}

} // namespace

bool separate(const Polygon2& p, const Vec2& from, int vertex, const Vec2& dir_in, std::array<Polygon2, 2>& out,
              Vec2* cut_from, Vec2* cut_to)
{
	// Keep every other vertex clearly off the line: turn it about the notch (or slide it, for a
	// hole's line) by tiny amounts until none is within `gap` (the paper's perturbation).
	const double size = extent2(p.outer);
	const double gap  = 1e-9 * size;
	// First the exact line from a notch, allowed to end at a vertex on it (notch to notch).
	if (vertex >= 0 && separate_at(p, from, vertex, dir_in.normalized(), out, cut_from, cut_to, gap)) return true;
	for (double off : {0.0, 1e-7, -1e-7, 3.1e-7, -3.1e-7, 1.3e-6, -1.3e-6}) {
		Vec2 dir = dir_in.normalized(), at = from;
		if (vertex >= 0) dir = Eigen::Rotation2Dd(off) * dir;
		else at += off * size * Vec2(-dir.y(), dir.x());
		bool clear = true;
		for (int l = 0; l <= (int) p.holes.size() && clear; ++l) {
			const Loop2& L = loop_of(p, l);
			for (int i = 0; i < (int) L.size(); ++i)
				if (!(l == 0 && i == vertex) && std::abs(cross(dir, L[i] - at)) <= gap) {
					clear = false;
					break;
				}
		}
		if (clear && separate_at(p, at, vertex, dir, out, cut_from, cut_to)) return true;
	}
	return false;
}

namespace {

// Directed boundary edges: of the faces (an edge whose reverse is not used), else the edges.
std::vector<Edge> boundary_edges(const std::vector<Vec3>& V, const std::vector<Tri>& F, const std::vector<Edge>& E)
{
	std::vector<Edge> boundary;
	if (!F.empty()) {
		std::set<std::pair<int, int>> directed;
		for (const Tri& t : F)
			for (int k = 0; k < 3; ++k) directed.insert({t[k], t[(k + 1) % 3]});
		for (const auto& [a, b] : directed)
			if (!directed.count({b, a})) boundary.push_back({a, b});
		if (boundary.empty()) invalid("The mesh has no boundary: a closed surface is not a planar polygon.");
	}
	else boundary = E;
	if (boundary.empty()) invalid("The layer has neither faces nor edges: nothing outlines a polygon.");
	for (const Edge& e : boundary)
		if (e[0] < 0 || e[1] < 0 || e[0] >= (int) V.size() || e[1] >= (int) V.size() || e[0] == e[1])
			invalid("An edge has an invalid vertex index.");
	return boundary;
}

// Chain the edges into loops of vertex ids. Faces give directions; bare edges (`directed` false) are
// undirected (each vertex on two).
std::vector<std::vector<int>> chain_loops(const std::vector<Edge>& boundary, bool directed)
{
	std::map<int, std::vector<int>> link;
	for (const Edge& e : boundary) {
		link[e[0]].push_back(e[1]);
		if (!directed) link[e[1]].push_back(e[0]);
	}
	for (const auto& [v, out] : link) {
		if (out.size() == (directed ? 1u : 2u)) continue;
		if (!directed)
			invalid("The edges do not form closed loops: a vertex has " + std::to_string(out.size()) +
			        " edges (each needs exactly 2).");
		throw Error(Error::InvalidInput, "The mesh's boundary touches itself at a vertex (non-manifold boundary).",
		            Error::NonManifoldBoundary);
	}
	std::set<int>                 used;
	std::vector<std::vector<int>> loops;
	for (const auto& [start, out] : link) {
		if (used.count(start)) continue;
		std::vector<int> L;
		int              prev = -1, v = start;
		do {
			used.insert(v);
			L.push_back(v);
			const std::vector<int>& nx = link[v];
			const int next = nx.size() == 1 || nx[0] != prev ? nx[0] : nx[1];
			prev = v;
			v    = next;
			if (!link.count(v)) invalid("The boundary edges do not close into loops.");
		} while (v != start && L.size() <= link.size());
		if (v != start) invalid("The boundary edges do not close into loops.");
		loops.push_back(std::move(L));
	}
	return loops;
}

// The plane's frame from the principal axes of the points; with faces, their side is the front (loops
// then come out counter-clockwise). Refused unless the points are planar to 1e-6 of their size.
void fit_plane(const std::vector<Vec3>& pts, const std::vector<Vec3>& V, const std::vector<Tri>& F, PlanarLoops& out)
{
	for (const Vec3& p : pts) out.origin += p;
	out.origin /= (double) pts.size();
	Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
	for (const Vec3& p : pts) C += (p - out.origin) * (p - out.origin).transpose();
	Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
	out.n = es.eigenvectors().col(0);
	out.u = es.eigenvectors().col(2);
	if (!F.empty()) {
		Vec3 sum = Vec3::Zero();
		for (const Tri& t : F) sum += (V[t[1]] - V[t[0]]).cross(V[t[2]] - V[t[0]]);
		if (sum.dot(out.n) < 0) out.n = -out.n;
	}
	out.w = out.n.cross(out.u);
	const double size = extent(pts);
	if (!(size > 0)) invalid("The polygon is degenerate: all its points coincide.");
	double off = 0;
	for (const Vec3& p : pts) off = std::max(off, std::abs(out.n.dot(p - out.origin)));
	if (off > 1e-6 * size)
		invalid("The outline is not planar (a point lies " + std::to_string(off / size) +
		        " of the size off its best-fitting plane); the polygon filter needs a planar layer.");
}

} // namespace

PlanarLoops planar_loops(const std::vector<Vec3>& V, const std::vector<Tri>& F, const std::vector<Edge>& E)
{
	const std::vector<std::vector<int>> index_loops = chain_loops(boundary_edges(V, F, E), !F.empty());
	std::vector<Vec3>                   pts;
	for (const auto& L : index_loops)
		for (int v : L) {
			if (!V[v].allFinite()) invalid("The polygon has NaN or infinite coordinates.");
			pts.push_back(V[v]);
		}
	PlanarLoops out;
	fit_plane(pts, V, F, out);
	for (const auto& L : index_loops) {
		Loop2 l;
		for (int v : L) l.emplace_back(out.u.dot(V[v] - out.origin), out.w.dot(V[v] - out.origin));
		out.loops.push_back(std::move(l));
	}
	return out;
}

std::vector<int> Decomposition2::leaves() const
{
	std::vector<int> l;
	for (int i = 0; i < (int) nodes.size(); ++i)
		if (nodes[i].leaf()) l.push_back(i);
	std::sort(l.begin(), l.end(), [&](int a, int b) { return nodes[a].path < nodes[b].path; });
	return l;
}

double Decomposition2::max_leaf_concavity() const
{
	double c = 0;
	for (int i : leaves()) c = std::max(c, nodes[i].concavity);
	return c;
}

namespace {

// Principal axes of a hole's boundary (length-weighted, so the sampling does not matter) and its
// centre: columns of `axes` major first.
void hole_axes(const Loop2& H, Vec2& centre, Eigen::Matrix2d& axes)
{
	double          len = 0;
	Vec2            c   = Vec2::Zero();
	Eigen::Matrix2d M   = Eigen::Matrix2d::Zero();
	for (size_t i = 0; i < H.size(); ++i) {
		const Vec2 &a = H[i], &b = H[(i + 1) % H.size()];
		const double w = (b - a).norm();
		len += w;
		c += w * (a + b) / 2;
		M += w / 6 * (2 * a * a.transpose() + 2 * b * b.transpose() + a * b.transpose() + b * a.transpose());
	}
	c /= len;
	centre = c;
	Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(M / len - c * c.transpose());
	axes.col(0) = es.eigenvectors().col(1);
	axes.col(1) = es.eigenvectors().col(0);
}

struct Scored
{
	double conc = 0;   // a piece's concavity for scoring: notches, and holes by their depth
	int    holes = 0;
};

Scored score(const Polygon2& p, bool keep)
{
	const Concavity2 c = measure_concavity(p);
	Scored           s{c.max_concavity, (int) p.holes.size()};
	if (!keep)
		for (double d : c.hole_depth) s.conc = std::max(s.conc, d);
	return s;
}

Line2 line_through(const Vec2& p, const Vec2& dir)
{
	Line2 l;
	l.n = Vec2(-dir.y(), dir.x()).normalized();
	l.d = l.n.dot(p);
	return l;
}

// A candidate cut: from a point (an outer vertex, or -1 for a hole's centre) along a direction.
struct Cand
{
	Vec2 from, dir;
	int  vertex;
};

struct Trial2
{
	std::array<Polygon2, 2> parts;
	Vec2                    a, b;
	bool                    ok = false, crosses = false;
	double                  score = 0, sum = 0;
};

// One polygon's cut: its target (the most concave notch, or a hole), candidate lines, their trials.
struct Cut2
{
	int                 id = -1, hole = -1;
	std::vector<Cand>   cands;
	std::vector<Trial2> trials;
	bool                first_fit = false;
	int                 pick = -1;
};

// Algorithm 5.3 for a polygon with holes, as named stages; the recursion is the one 3D uses.
class Driver2 : public Driving<Driver2, Decomposition2, PolygonOptions>
{
public:
	explicit Driver2(const PolygonOptions& opt) : Driving(opt, opt.hole_handling == HoleCut::KeepHoles, kMaxDepth) {}

	Decomposition2 run(const Polygon2& poly) { return finish({add_node(poly, -1, "0")}, &Decomposition2::kept_holes); }

	int cut(int id)
	{
		Cut2 c;
		c.id = id;
		choose_target(c);
		if (c.hole >= 0) hole_lines(c);
		else notch_lines(c);
		try_lines(c);
		pick_line(c);
		return accept(c);
	}

	void forget(int) {}

private:
	std::vector<Concavity2> measured;

	int add_node(Polygon2 p, int parent, const std::string& path)
	{
		Node2 n;
		n.parent           = parent;
		n.path             = path;
		n.polygon          = std::move(p);
		const Concavity2 c = measure_concavity(n.polygon);
		n.concavity        = c.max_concavity;
		n.notch_count      = c.notches;
		n.hole_count       = (int) n.polygon.holes.size();
		n.area             = area(n.polygon);
		if (c.max_vertex >= 0) n.notch = n.polygon.outer[c.max_vertex];
		D.nodes.push_back(std::move(n));
		measured.push_back(c);
		return (int) D.nodes.size() - 1;
	}

	// Which hole, if any: holes first (the paper), or when a hole is deeper than every notch, or when
	// only holes are left.
	void choose_target(Cut2& c) const
	{
		const Polygon2&   P = D.nodes[c.id].polygon;
		const Concavity2& m = measured[c.id];
		if (keep || P.holes.empty()) return;
		c.hole = (int) (std::max_element(m.hole_depth.begin(), m.hole_depth.end()) - m.hole_depth.begin());
		if (opt.hole_order == HoleOrder::ByConcavity && m.hole_depth[c.hole] <= m.max_concavity && m.max_concavity > opt.tau)
			c.hole = -1;
	}

	// Through the hole's centre: the paper's principal axis first, the minor axis, then a fan.
	void hole_lines(Cut2& c) const
	{
		Vec2            centre;
		Eigen::Matrix2d axes;
		hole_axes(D.nodes[c.id].polygon.holes[c.hole], centre, axes);
		c.cands.push_back({centre, axes.col(0), -1});
		c.cands.push_back({centre, axes.col(1), -1});
		for (int k = 1; k < 8; ++k)
			if (k != 4) c.cands.push_back({centre, Eigen::Rotation2Dd(M_PI * k / 8) * axes.col(0), -1});
		c.first_fit = opt.hole_handling != HoleCut::BestLine;
	}

	// The bisector of the notch's incident edge normals, pointing into the polygon (Algorithm 5.1's
	// cut line); it lies between u1 and u2, the directions that resolve the notch. With Best also
	// the cone between them, its own edges (a cut continuing an edge can reach the next notch in
	// line) and the directions towards the nearest notches inside it (cutting two at once).
	void notch_lines(Cut2& c) const
	{
		const Polygon2&   P = D.nodes[c.id].polygon;
		const Concavity2& m = measured[c.id];
		const int         n = (int) P.outer.size(), r = m.max_vertex;
		const Vec2 prev = P.outer[(r + n - 1) % n], cur = P.outer[r], next = P.outer[(r + 1) % n];
		const Vec2 u1 = (cur - prev).normalized(), u2 = (cur - next).normalized();   // edges extended past r
		Vec2       bis = u1 + u2;
		if (bis.norm() < 1e-12) bis = Vec2(-u1.y(), u1.x());
		c.cands.push_back({cur, bis.normalized(), r});
		c.first_fit = opt.cut_line_selection == CutLineSelection::Bisector;
		if (c.first_fit) return;
		const double span = std::atan2(cross(u1, u2), u1.dot(u2));   // from u1 to u2
		const int    k_max = std::max(2, opt.candidate_lines);
		for (int k = 0; k <= k_max + 1; ++k) c.cands.push_back({cur, Eigen::Rotation2Dd(span * k / (k_max + 1)) * u1, r});
		std::vector<std::pair<double, int>> near;
		for (int v = 0; v < n; ++v)
			if (v != r && m.outer[v] > opt.tau) near.push_back({(P.outer[v] - cur).norm(), v});
		std::sort(near.begin(), near.end());
		for (size_t i = 0; i < near.size() && i < 6; ++i) {
			const Vec2   d   = (P.outer[near[i].second] - cur).normalized();
			const double a   = std::atan2(cross(u1, d), u1.dot(d));
			const double tol = 1e-9;
			if ((span > 0 && a > -tol && a < span + tol) || (span < 0 && a < tol && a > span - tol)) c.cands.push_back({cur, d, r});
		}
	}

	// Split by candidate i; unless first-fit, score the pieces (notches, and holes by their depth).
	void trial(Cut2& c, size_t i) const
	{
		const Polygon2& P  = D.nodes[c.id].polygon;
		Trial2&         t  = c.trials[i];
		if (!separate(P, c.cands[i].from, c.cands[i].vertex, c.cands[i].dir, t.parts, &t.a, &t.b)) return;
		const double a0 = D.nodes[c.id].area;
		if (area(t.parts[0]) < 1e-9 * a0 || area(t.parts[1]) < 1e-9 * a0) return;
		const int holes_after = (int) (t.parts[0].holes.size() + t.parts[1].holes.size());
		if (c.hole >= 0 && holes_after >= (int) P.holes.size()) return;   // missed the hole
		t.crosses = keep && holes_after < (int) P.holes.size();
		t.ok      = true;
		if (c.first_fit) return;
		const Scored x = score(t.parts[0], keep), y = score(t.parts[1], keep);
		t.score = std::max(x.conc, y.conc);
		t.sum   = x.conc + y.conc;
	}

	void try_lines(Cut2& c) const
	{
		c.trials.assign(c.cands.size(), Trial2());
		if (!c.first_fit) {
			parallel_for(c.cands.size(), [&](size_t i) { trial(c, i); });
			return;
		}
		for (size_t i = 0; i < c.cands.size(); ++i) {
			trial(c, i);
			if (c.trials[i].ok && !c.trials[i].crosses) break;
		}
	}

	// The least concave pieces (ties by the total). As in 3D, the paper's bisector stands unless
	// another direction is clearly (10%) better; here also when it leaves the same worst concavity
	// but clearly less in total (a cut resolving two notches at once, as across a comb's tooth).
	void pick_line(Cut2& c) const
	{
		const double hair = 1e-9;
		const auto&  T    = c.trials;
		int          pick = -1;
		for (const bool allow_crossing : {false, true}) {
			for (int i = 0; i < (int) T.size(); ++i) {
				const Trial2& t = T[i];
				if (!t.ok || (t.crosses && !allow_crossing)) continue;
				if (pick < 0 || t.score < T[pick].score - hair || (t.score <= T[pick].score + hair && t.sum < T[pick].sum - hair))
					pick = i;
			}
			if (pick >= 0) break;
		}
		if (c.hole < 0 && pick > 0 && T[0].ok && !T[0].crosses) {
			const Trial2 &b = T[0], &t = T[pick];
			const bool better = t.score < 0.9 * b.score || (t.score <= b.score + hair && t.sum < 0.9 * b.sum);
			if (!better) pick = 0;
		}
		c.pick = pick;
	}

	int accept(Cut2& c)
	{
		const int id = c.id;
		if (c.pick < 0) {
			D.nodes[id].uncut = true;
			return 0;
		}
		Trial2& t = c.trials[c.pick];
		Node2&  nd = D.nodes[id];
		nd.has_cut  = true;
		nd.cut_from = t.a;
		nd.cut_to   = t.b;
		nd.line     = line_through(t.a, t.b - t.a);
		nd.hole_cut = c.hole >= 0;
		D.hole_cuts += c.hole >= 0;
		const std::string path = nd.path;
		for (int s = 0; s < 2; ++s) {
			const int ch         = add_node(std::move(t.parts[s]), id, path + char('0' + s));
			D.nodes[id].child[s] = ch;
			rec.push(ch);
		}
		return 1;
	}

	// Greedy cuts peel a comb's teeth one per level: deeper trees than in 3D are normal.
	static constexpr size_t kMaxDepth = 200;
};

} // namespace

Decomposition2 decompose(const Polygon2& polygon, const PolygonOptions& opt)
{
	if (!(opt.tau > 0) || !std::isfinite(opt.tau))
		throw Error(Error::InvalidOption, "tau must be a positive, finite length.");
	if (opt.max_parts < 0) throw Error(Error::InvalidOption, "max_parts must be 0 (unbounded) or positive.");
	// Centred, unit-size coordinates (as in 3D), mapped back at the end.
	Vec2 c = Vec2::Zero();
	for (const Vec2& p : polygon.outer) c += p;
	c /= (double) polygon.outer.size();
	const double s = extent2(polygon.outer);
	auto         to_unit = [&](Loop2 l) {
        for (Vec2& p : l) p = (p - c) / s;
        return l;
	};
	Polygon2 unit{to_unit(polygon.outer), {}};
	for (const Loop2& h : polygon.holes) unit.holes.push_back(to_unit(h));
	PolygonOptions o = opt;
	o.tau /= s;
	Decomposition2 D = Driver2(o).run(unit);
	D.tau = opt.tau;
	auto back = [&](Vec2& p) { p = p * s + c; };
	for (Node2& n : D.nodes) {
		for (Vec2& p : n.polygon.outer) back(p);
		for (Loop2& h : n.polygon.holes)
			for (Vec2& p : h) back(p);
		n.concavity *= s;
		n.area *= s * s;
		back(n.notch);
		back(n.cut_from);
		back(n.cut_to);
		n.line.d = n.line.d * s + n.line.n.dot(c);
	}
	return D;
}

} // namespace acd
