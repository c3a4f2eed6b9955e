#include "acd/polygon/polygon.h"
#include "acd/polygon/geometry2.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <vector>

namespace acd {

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

} // namespace acd
