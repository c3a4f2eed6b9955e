#include "acd/decompose3/concavity.h"
#include "acd/hull/hull_reach.h"
#include "acd/mesh/parallel.h"
#include "acd/mesh/measures.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace acd {

namespace {

// A* on the mesh's edge graph with the straight-line distance as the (admissible) heuristic.
// Per-vertex state lives in one array reused across searches (a vertex's entries side by side: one
// cache line read per neighbour looked at); a stamp tells this search's entries.
struct PathSearch
{
	struct State
	{
		double g = 0, h = 0;   // h: the heuristic, computed once per vertex and search
		int    from = 0, stamp = 0;
	};
	std::vector<State> state;
	int                round = 0;
	using Item = std::pair<double, int>;
	std::vector<Item>  heap;

	// Stamps only grow, so a search reused on another mesh never sees stale entries as current.
	void resize(int nv)
	{
		if ((int) state.size() == nv) return;
		state.assign(nv, State{});
	}

	// Stores the path's vertices, p first, in `out`; returns false if q is unreachable from p.
	bool run(const TriMesh& m, const Topology& t, int p, int q, std::vector<int>& out)
	{
		++round;
		heap.clear();
		const Vec3& goal = m.V[q];
		auto        push = [&](double f, int v) {
            heap.emplace_back(f, v);
            std::push_heap(heap.begin(), heap.end(), std::greater<Item>());
		};
		state[p].g     = 0;
		state[p].h     = (m.V[p] - goal).norm();
		state[p].stamp = round;
		push(state[p].h, p);
		bool found = false;
		while (!heap.empty()) {
			std::pop_heap(heap.begin(), heap.end(), std::greater<Item>());
			auto [f, v] = heap.back();
			heap.pop_back();
			const double gv = state[v].g;
			if (f > gv + state[v].h + 1e-300) continue;   // stale entry
			if (v == q) {
				found = true;
				break;
			}
			const Vec3& x = m.V[v];
			t.for_each_neighbour(v, [&](int w) {
				State&       sw = state[w];
				const double gw = gv + (m.V[w] - x).norm();
				if (sw.stamp != round) {
					sw.stamp = round;
					sw.h     = (m.V[w] - goal).norm();
				}
				else if (!(gw < sw.g)) return;
				sw.g    = gw;
				sw.from = v;
				push(gw + sw.h, w);
			});
		}
		if (!found) return false;
		for (int v = q; v != p; v = state[v].from) out.push_back(v);
		out.push_back(p);
		std::reverse(out.begin(), out.end());   // p ... q
		return true;
	}
};

// Algorithm 6.1 in stages; each method is one numbered step and leaves its result in the members.
struct Measure
{
	const TriMesh&    m;
	const Topology&   topo;
	const ConvexHull& hull;
	const int         nf, nv;
	const double      diag, eps;
	ConcavityReport   r;

	std::vector<double> vdist;        // exact distance to the hull's boundary, -1 if not computed
	std::vector<double> lower;        // a lower bound of it, -1 until the vertex is visited
	std::vector<int>    nearest;      // hull triangle nearest to the vertex, or to a neighbour
	std::vector<int>    face_facet;   // hull facet holding an on-hull face, else -1
	std::vector<char>   bridge;       // per hull facet: not covered by the surface
	std::vector<char>   on_path;      // per directed edge (face corner 3f+k): a bridge path uses it
	std::vector<std::pair<int, int>> corner_votes;   // (3f+k, facet on the left of that edge)
	std::vector<int>    patch, pocket;                // per face, -1 on the hull
	std::vector<std::vector<int>> patch_bridges;
	std::vector<int>    notch_vertices;

	Measure(const TriMesh& m, const Topology& topo, const ConvexHull& hull)
	    : m(m), topo(topo), hull(hull), nf((int) m.F.size()), nv((int) m.V.size()), diag(extent(hull.points)),
	      eps(1e-9 * diag)
	{
		r.vertex_concavity.assign(nv, 0.0);
		r.vertex_bridge.assign(nv, -1);
	}

	// Everything below walks across edges; an open part (only a broken input can make one) would
	// send it out of bounds.
	void require_closed() const
	{
		for (const auto& nb : topo.neighbour)
			if (nb[0] < 0 || nb[1] < 0 || nb[2] < 0)
				throw Error(Error::InvalidInput,
				            "A cut made a part that is not closed: the mesh intersects itself there (preprocessing "
				            "alpha_wrap repairs it).",
				            Error::OpenPart);
	}

	bool on_hull(int v) const { return vdist[v] >= 0 && vdist[v] <= eps; }

	// 1a. Distances of the vertices to the hull's boundary, where they can be near it. A vertex's
	//     distance is 1-Lipschitz, so a neighbour's distance minus the edge length bounds it from
	//     below: visiting vertices outward from the hull vertices, deep ones are ruled out without a
	//     query (queries from deep points are the slow ones).
	void hull_distances()
	{
		vdist.assign(nv, -1.0);
		lower.assign(nv, -1.0);
		nearest.assign(nv, -1);
		std::vector<int> queue;
		queue.reserve(nv);
		int unvisited = 0;
		for (int i = 0; i < (int) hull.point_source.size(); ++i) {
			const int v = hull.point_source[i];
			if (lower[v] < 0) {
				vdist[v] = lower[v] = 0;
				nearest[v]          = hull.point_triangle[i];
				queue.push_back(v);
			}
		}
		for (size_t head = 0; head < queue.size() || (int) queue.size() < nv; ++head) {
			if (head == queue.size()) {   // a shell without hull vertices (a cavity)
				while (lower[unvisited] >= 0) ++unvisited;
				const int v = unvisited;
				vdist[v] = lower[v] = hull.distance_to_boundary(m.V[v], &nearest[v]);
				queue.push_back(v);
			}
			const int q = queue[head];
			topo.for_each_neighbour(q, [&](int v) {
				if (lower[v] >= 0) return;
				const double lb = lower[q] - (m.V[v] - m.V[q]).norm();
				if (lb > eps) {
					lower[v]   = lb;
					nearest[v] = nearest[q];
				}
				else vdist[v] = lower[v] = hull.distance_to_boundary(m.V[v], &nearest[v], nearest[q]);
				queue.push_back(v);
			});
		}
	}

	// 1b. Surface faces on the hull: all three corners and the centroid on the hull's boundary (a face
	//     joining points of different facets cuts through the inside, so its centroid is deep).
	//     2. Bridges: hull facets the surface does not cover.
	void coverage_and_bridges()
	{
		face_facet.assign(nf, -1);
		std::vector<double> covered(hull.facets(), 0.0);
		for (int f = 0; f < nf; ++f) {
			const Tri& t = m.F[f];
			if (!on_hull(t[0]) || !on_hull(t[1]) || !on_hull(t[2])) continue;
			int tri = -1;
			if (hull.distance_to_boundary((m.V[t[0]] + m.V[t[1]] + m.V[t[2]]) / 3.0, &tri, nearest[t[0]]) > eps)
				continue;
			const Vec3 n  = (m.V[t[1]] - m.V[t[0]]).cross(m.V[t[2]] - m.V[t[0]]);
			face_facet[f] = hull.facet_facing(tri, n.normalized());
			covered[face_facet[f]] += 0.5 * n.norm();
		}
		bridge.assign(hull.facets(), 0);
		for (int b = 0; b < hull.facets(); ++b)
			if (covered[b] < hull.facet_area[b] * (1 - 1e-9)) {
				bridge[b] = 1;
				++r.bridges;
			}
	}

	struct PathTask
	{
		int              p, q, left, right;   // path ends; facets left and right of p->q (-1: not a bridge)
		std::vector<int> path;
	};

	// 3a. One path per edge of the polytope bordering a bridge, i.e. per chain of hull edges between
	//     the same two facets. Chains, not single hull edges, because a cut across an earlier cap
	//     leaves a row of collinear points on the hull, and which of them count as hull vertices is
	//     decided by rounding (so by the pose).
	std::vector<PathTask> path_tasks() const
	{
		std::vector<PathTask> tasks;
		// Directed hull edges p->q with the facet on their left, grouped by the facets' pair.
		std::map<std::pair<int, int>, std::vector<std::array<int, 2>>> chains;   // (left, right) -> edges
		std::map<std::pair<int, int>, int> left_of;   // directed hull edge -> facet on its left
		for (int t = 0; t < (int) hull.triangles.size(); ++t)
			for (int k = 0; k < 3; ++k)
				left_of[{hull.triangles[t][k], hull.triangles[t][(k + 1) % 3]}] = hull.triangle_facet[t];
		for (const auto& [e, fl] : left_of) {
			auto it = left_of.find({e.second, e.first});
			if (it == left_of.end() || it->second == fl || (!bridge[fl] && !bridge[it->second])) continue;
			if (fl < it->second) chains[{fl, it->second}].push_back({e.first, e.second});
		}
		for (const auto& [facets, edges] : chains) {
			const int left = bridge[facets.first] ? facets.first : -1, right = bridge[facets.second] ? facets.second : -1;
			// Two faces of a convex polytope share one segment: walk it from the end no edge enters.
			std::map<int, int> next, indeg;
			for (const auto& e : edges) {
				next[e[0]] = e[1];
				++indeg[e[1]];
			}
			int start = -1;
			for (const auto& e : edges)
				if (!indeg.count(e[0])) start = start < 0 ? e[0] : -2;
			size_t steps = 0;
			int    end   = start;
			while (start >= 0 && next.count(end) && steps <= edges.size()) end = next[end], ++steps;
			if (start >= 0 && steps == edges.size()) {
				tasks.push_back({hull.point_source[start], hull.point_source[end], left, right, {}});
				continue;
			}
			for (const auto& e : edges)   // not one segment (facets merged around a bend): edge by edge
				tasks.push_back({hull.point_source[e[0]], hull.point_source[e[1]], left, right, {}});
		}
		return tasks;
	}

	// 3b. Shortest surface paths for the tasks. A path from p to q, where p->q runs counter-clockwise
	//     around facet B seen from outside, has B's region on its left: the face holding the directed
	//     mesh edge (a,b) of the path votes for B, the face holding (b,a) for the facet on the other side.
	void bridge_paths()
	{
		std::vector<PathTask> tasks = path_tasks();
		on_path.assign(3 * nf, 0);
		// Paths are independent: search them on all cores in chunks, then record them in order.
		parallel_for_chunked(tasks.size(), 64, [&](size_t i) {
			thread_local PathSearch search;
			search.resize(nv);
			if (!search.run(m, topo, tasks[i].p, tasks[i].q, tasks[i].path)) tasks[i].path.clear();
		});
		for (const PathTask& t : tasks)
			for (size_t i = 0; i + 1 < t.path.size(); ++i) {
				const int fwd = topo.corner(t.path[i], t.path[i + 1]), bwd = topo.corner(t.path[i + 1], t.path[i]);
				on_path[fwd] = on_path[bwd] = 1;
				if (t.left >= 0) corner_votes.emplace_back(fwd, t.left);
				if (t.right >= 0) corner_votes.emplace_back(bwd, t.right);
			}
	}

	// Faces off the hull connected across edges (not crossing a path if `respect_paths`); the count.
	int flood(std::vector<int>& label, bool respect_paths) const
	{
		label.assign(nf, -1);
		std::vector<int> stack;
		int              count = 0;
		for (int s = 0; s < nf; ++s) {
			if (face_facet[s] >= 0 || label[s] >= 0) continue;
			label[s] = count;
			stack.assign(1, s);
			while (!stack.empty()) {
				int f = stack.back();
				stack.pop_back();
				for (int k = 0; k < 3; ++k) {
					int g = topo.neighbour[f][k];
					if (g < 0 || face_facet[g] >= 0 || label[g] >= 0) continue;
					if (respect_paths && on_path[3 * f + k]) continue;
					label[g] = count;
					stack.push_back(g);
				}
			}
			++count;
		}
		return count;
	}

	// 4. Patches: pocket faces connected across edges no path uses. Pockets: the same, ignoring paths.
	void patches()
	{
		r.patches = flood(patch, true);
		r.pockets = flood(pocket, false);
	}

	double edge_length(int c) const { return (m.V[m.F[c / 3][c % 3]] - m.V[m.F[c / 3][(c % 3 + 1) % 3]]).norm(); }

	// 5. Each patch belongs to the bridge whose paths bound it from the bridge's side; a patch no path
	//    bounds (a dimple in a partly covered facet) to the bridges of the hull faces around it. A
	//    patch bounded by several bridges (the two lids of a torus's hole, or a lid the cuts broke into
	//    several nearly coplanar facets) lets each vertex retract to the nearest of them.
	void associate()
	{
		std::vector<std::map<int, double>> votes(r.patches), touch(r.patches);
		for (const auto& [c, fct] : corner_votes)
			if (patch[c / 3] >= 0) votes[patch[c / 3]][fct] += edge_length(c);
		for (int f = 0; f < nf; ++f) {
			if (patch[f] < 0) continue;
			for (int k = 0; k < 3; ++k) {
				const int g = topo.neighbour[f][k];
				if (g >= 0 && face_facet[g] >= 0 && bridge[face_facet[g]])
					touch[patch[f]][face_facet[g]] += edge_length(3 * f + k);
			}
		}
		patch_bridges.assign(r.patches, {});
		for (int p = 0; p < r.patches; ++p) {
			if (votes[p].empty()) votes[p] = touch[p];
			for (const auto& fw : votes[p]) patch_bridges[p].push_back(fw.first);
		}
	}

	// 6. Concavity of each pocket vertex: distance to its patch's nearest bridge (or, for a patch no
	//    bridge bounds, such as a closed cavity, to the hull). A facet is no nearer than its plane,
	//    so bridges are tried nearest plane first and the rest skipped once a facet is nearer.
	void distances()
	{
		std::vector<long long> pairs;   // (vertex, patch), each once
		pairs.reserve(3 * nf);
		for (int f = 0; f < nf; ++f)
			if (patch[f] >= 0)
				for (int v : m.F[f]) pairs.push_back((static_cast<long long>(v) << 32) | patch[f]);
		std::sort(pairs.begin(), pairs.end());
		pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
		std::vector<std::pair<double, int>> near;
		for (long long vp : pairs) {
			const int   v = (int) (vp >> 32), p = (int) (vp & 0xffffffff);
			const Vec3& x = m.V[v];
			double      d = 0;
			int         b = -1;
			if (patch_bridges[p].empty()) {
				if (vdist[v] < 0) vdist[v] = hull.distance_to_boundary(x, nullptr, nearest[v]);
				d = vdist[v];
			}
			else {
				near.clear();
				for (int fct : patch_bridges[p]) near.emplace_back(std::max(0.0, -hull.facet_plane[fct].eval(x)), fct);
				std::sort(near.begin(), near.end());
				for (const auto& [plane_dist, fct] : near) {
					if (b >= 0 && plane_dist >= d) break;
					const double df = hull.distance_to_facet(x, fct);
					if (b < 0 || df < d) d = df, b = fct;
				}
			}
			if (d > r.vertex_concavity[v]) {
				r.vertex_concavity[v] = d;
				r.vertex_bridge[v]    = b;
			}
		}
	}

	// 7. Notches (reflex edges) and the most concave one. Concavities equal to rounding are ties,
	//    settled by position in the part's own principal frame: the same notch in every pose and
	//    vertex order (a mirror-symmetric pair of notches would otherwise go either way).
	void notches()
	{
		r.frame                = pose_frame(m);
		const PoseFrame& frame = r.frame;
		for (int f = 0; f < nf; ++f)
			for (int k = 0; k < 3; ++k) {
				const int g = topo.neighbour[f][k];
				if (g < f || !is_reflex(m, topo, f, k)) continue;
				++r.notches;
				for (int v : {m.F[f][k], m.F[f][(k + 1) % 3]}) {
					notch_vertices.push_back(v);
					const double c = r.vertex_concavity[v];
					if (!(c > 0) || v == r.max_vertex) continue;
					const bool better = r.max_vertex < 0 || c > r.max_concavity + frame.tol ||
					                    (c >= r.max_concavity - frame.tol && frame.before(m.V[v], m.V[r.max_vertex]));
					if (better) {
						r.max_concavity = c;
						r.max_vertex    = v;
						r.max_bridge    = r.vertex_bridge[v];
					}
				}
			}
	}

	// 8. The bridges' reach: how far the hull lies from the surface across each bridge. Between the
	//    vertices of a sparse pocket (a bore's wall, a slot's flank: every vertex on the hull) the
	//    distances above see nothing, while the hull stands off the surface by the pocket's width.
	//    The pocket's own concavity is at least that reach, so the farthest bridge point is charged
	//    to the notch nearest to the surface point it faces, and that notch is cut next.
	//    In a decomposition the reach decides only for a part its notches call tau-convex (a part
	//    over tau is cut at its notches anyway; letting the reach compete there would let the
	//    refinement's rounding, which follows the pose, pick the notch). It is refined to 1% of tau
	//    below tau, which certifies the hull within tau, and to 2% above.
	void reach(double tau, Reach which)
	{
		if (which == Reach::Left || (tau > 0 && r.max_concavity > tau && which != Reach::Always)) return;
		const HullReach hr    = bridges_reach(m, hull, bridge, tau, r.max_concavity);
		r.hull_reach          = hr.lower;
		r.hull_reach_bound    = hr.upper;
		const double c        = reach_charge(hr, hull, tau, r.max_concavity);
		if (c <= r.max_concavity) return;   // within the bar, or notches over tau already (Reach::Always)
		const int    v        = notch_nearest(hr.nearest);
		r.vertex_concavity[v] = std::max(r.vertex_concavity[v], c);
		r.max_concavity       = c;
		r.max_vertex          = v;
		r.max_bridge          = hr.facet;
		r.reach_cut           = true;
	}

	// The notch vertex nearest to `x` (any vertex when no edge is reflex beyond rounding: a pocket of
	// nearly flat folds); ties by the part's frame.
	int notch_nearest(const Vec3& x)
	{
		if (notch_vertices.empty())
			for (int u = 0; u < nv; ++u) notch_vertices.push_back(u);
		const PoseFrame& frame = r.frame;
		int              v     = -1;
		double           best  = 0;
		for (int u : notch_vertices) {
			const double d = (m.V[u] - x).norm();
			if (v < 0 || d < best - frame.tol || (d <= best + frame.tol && frame.before(m.V[u], m.V[v]))) best = d, v = u;
		}
		return v;
	}
};

// What the reach is measured against: tau, or with tau 0 the deepest notch; and the slack beyond it.
std::pair<double, double> reach_floor(const ConvexHull& hull, double tau, double deepest)
{
	return {tau > 0 ? tau : deepest, tau > 0 ? 0.01 * tau : 1e-3 * extent(hull.points)};
}

} // namespace

HullReach bridges_reach(const TriMesh& m, const ConvexHull& hull, const std::vector<char>& bridge, double tau,
                        double deepest)
{
	const auto [floor, slack] = reach_floor(hull, tau, deepest);
	return hull_reach(m, hull, bridge, floor, slack, tau > 0 ? 0.02 : 0.002);
}

double reach_charge(const HullReach& hr, const ConvexHull& hull, double tau, double deepest)
{
	const auto [floor, slack] = reach_floor(hull, tau, deepest);
	// Over when not certified within tau (+ slack); for the measure alone, when it exceeds the notches.
	const bool over = tau > 0 ? hr.upper > floor + slack : hr.lower > floor + slack;
	if (hr.facet < 0 || !over) return 0;
	// Not certified is over tau, even where the search stopped below it (its work bound).
	return std::max(hr.lower, tau > 0 ? std::nextafter(floor, 2 * floor) : 0.0);
}

ConcavityReport measure_concavity(const TriMesh& m, const Topology& topo, const ConvexHull& hull, double tau,
                                  Reach reach)
{
	Measure s(m, topo, hull);
	s.require_closed();
	s.hull_distances();
	s.coverage_and_bridges();
	s.bridge_paths();
	s.patches();
	s.associate();
	s.distances();
	s.notches();
	s.reach(tau, reach);
	s.r.bridge = std::move(s.bridge);
	return std::move(s.r);
}

} // namespace acd
