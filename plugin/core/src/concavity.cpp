#include "acd/concavity.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <unordered_map>

namespace acd {

namespace {

// A* on the mesh's edge graph with the straight-line distance as the (admissible) heuristic.
// Stores the path's vertices, p first, in `out`; returns false if q is unreachable from p.
bool shortest_path(const TriMesh& m, const Topology& t, int p, int q, std::vector<int>& out,
                   std::unordered_map<int, double>& g, std::unordered_map<int, int>& from)
{
	g.clear();
	from.clear();
	using Item = std::pair<double, int>;
	std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
	const Vec3& goal = m.V[q];
	g[p]             = 0;
	open.emplace((m.V[p] - goal).norm(), p);
	while (!open.empty()) {
		auto [f, v] = open.top();
		open.pop();
		const double gv = g[v];
		if (f > gv + (m.V[v] - goal).norm() + 1e-300) continue;   // stale entry
		if (v == q) break;
		t.for_each_neighbour(v, [&](int w) {
			const double gw = gv + (m.V[w] - m.V[v]).norm();
			auto         it = g.find(w);
			if (it == g.end() || gw < it->second) {
				g[w]    = gw;
				from[w] = v;
				open.emplace(gw + (m.V[w] - goal).norm(), w);
			}
		});
	}
	if (!g.count(q)) return false;
	for (int v = q; v != p; v = from[v]) out.push_back(v);
	out.push_back(p);
	std::reverse(out.begin(), out.end());   // p ... q
	return true;
}

} // namespace

ConcavityReport measure_concavity(const TriMesh& m, const Topology& topo, const ConvexHull& hull)
{
	const int    nf   = (int) m.F.size();
	const int    nv   = (int) m.V.size();
	const double diag = bbox_diagonal(hull.points);
	const double eps  = 1e-9 * diag;

	ConcavityReport r;
	r.vertex_concavity.assign(nv, 0.0);
	r.vertex_bridge.assign(nv, -1);

	// 1. Surface faces on the hull: all three corners and the centroid on the hull's boundary
	//    (a face joining points of different facets cuts through the inside, so its centroid is deep).
	std::vector<double> vdist(nv);
	for (int v = 0; v < nv; ++v) vdist[v] = hull.distance_to_boundary(m.V[v]);
	std::vector<int>    face_facet(nf, -1);   // hull facet holding an on-hull face, else -1
	std::vector<double> covered(hull.facets(), 0.0);
	for (int f = 0; f < nf; ++f) {
		const Tri& t = m.F[f];
		if (vdist[t[0]] > eps || vdist[t[1]] > eps || vdist[t[2]] > eps) continue;
		int tri = -1;
		if (hull.distance_to_boundary((m.V[t[0]] + m.V[t[1]] + m.V[t[2]]) / 3.0, &tri) > eps) continue;
		face_facet[f] = hull.triangle_facet[tri];
		covered[face_facet[f]] += 0.5 * (m.V[t[1]] - m.V[t[0]]).cross(m.V[t[2]] - m.V[t[0]]).norm();
	}

	// 2. Bridges: hull facets the surface does not cover.
	std::vector<char> bridge(hull.facets(), 0);
	for (int b = 0; b < hull.facets(); ++b)
		if (covered[b] < hull.facet_area[b] * (1 - 1e-9)) {
			bridge[b] = 1;
			++r.bridges;
		}

	// 3. Shortest surface paths between the ends of every hull edge that borders a bridge. A path
	//    from p to q, where p->q runs counter-clockwise around facet B seen from outside, has B's
	//    region on its left: the face holding the directed mesh edge (a,b) of the path votes for B,
	//    the face holding (b,a) for the facet on the other side. Edges inside one merged coplanar
	//    facet are not facet edges and are skipped.
	std::unordered_map<long long, std::vector<int>> cut;   // directed mesh edge -> facets on its left
	auto directed = [](int a, int b) { return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b); };
	{
		std::map<std::pair<int, int>, std::array<int, 2>> hull_edges;   // (p<q) -> {facet left of p->q, of q->p}
		for (int t = 0; t < (int) hull.triangles.size(); ++t)
			for (int k = 0; k < 3; ++k) {
				const int a = hull.triangles[t][k], b = hull.triangles[t][(k + 1) % 3];
				auto [it, fresh] = hull_edges.emplace(std::make_pair(std::min(a, b), std::max(a, b)),
				                                      std::array<int, 2>{-1, -1});
				it->second[a < b ? 0 : 1] = hull.triangle_facet[t];
			}
		std::unordered_map<int, double> g;
		std::unordered_map<int, int>    from;
		std::vector<int>                path;
		for (const auto& [e, fc] : hull_edges) {
			if (fc[0] < 0 || fc[1] < 0 || fc[0] == fc[1]) continue;
			if (!bridge[fc[0]] && !bridge[fc[1]]) continue;
			path.clear();
			if (!shortest_path(m, topo, hull.point_source[e.first], hull.point_source[e.second], path, g, from))
				continue;
			for (size_t i = 0; i + 1 < path.size(); ++i) {
				if (bridge[fc[0]]) cut[directed(path[i], path[i + 1])].push_back(fc[0]);
				if (bridge[fc[1]]) cut[directed(path[i + 1], path[i])].push_back(fc[1]);
				cut.try_emplace(directed(path[i], path[i + 1]));
				cut.try_emplace(directed(path[i + 1], path[i]));
			}
		}
	}

	// 4. Patches: pocket faces connected across edges no path uses. Pockets: the same, ignoring paths.
	std::vector<int> patch(nf, -1), pocket(nf, -1);
	std::vector<int> stack;
	auto             flood = [&](std::vector<int>& label, bool respect_paths) {
        int count = 0;
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
                    if (respect_paths && cut.count(directed(m.F[f][k], m.F[f][(k + 1) % 3]))) continue;
                    label[g] = count;
                    stack.push_back(g);
                }
            }
            ++count;
        }
        return count;
	};
	r.patches = flood(patch, true);
	r.pockets = flood(pocket, false);

	// 5. Each patch belongs to the bridge whose paths bound it from the bridge's side; a patch no path
	//    bounds (a dimple in a partly covered facet) to the bridges of the hull faces around it.
	std::vector<std::map<int, double>> votes(r.patches), touch(r.patches);
	for (int f = 0; f < nf; ++f) {
		if (patch[f] < 0) continue;
		for (int k = 0; k < 3; ++k) {
			const int    a = m.F[f][k], b = m.F[f][(k + 1) % 3];
			const int    g = topo.neighbour[f][k];
			const double len = (m.V[a] - m.V[b]).norm();
			auto         it  = cut.find(directed(a, b));
			if (it != cut.end())
				for (int fct : it->second) votes[patch[f]][fct] += len;
			if (g >= 0 && face_facet[g] >= 0 && bridge[face_facet[g]]) touch[patch[f]][face_facet[g]] += len;
		}
	}
	for (int p = 0; p < r.patches; ++p)
		if (votes[p].empty()) votes[p] = touch[p];

	// A patch bounded by several bridges (the two lids of a torus's hole, or a lid the cuts broke
	// into several nearly coplanar facets) lets each vertex retract to the nearest of them.
	std::vector<std::vector<int>> patch_bridges(r.patches);
	for (int p = 0; p < r.patches; ++p)
		for (const auto& fw : votes[p]) patch_bridges[p].push_back(fw.first);

	// 6. Concavity of each pocket vertex: distance to its patch's bridge (or, for a patch no bridge
	//    bounds, such as a closed cavity, to the hull).
	for (int f = 0; f < nf; ++f) {
		if (patch[f] < 0) continue;
		for (int v : m.F[f]) {
			double d = vdist[v];
			int    b = -1;
			for (int fct : patch_bridges[patch[f]]) {
				const double df = hull.distance_to_facet(m.V[v], fct);
				if (b < 0 || df < d) d = df, b = fct;
			}
			if (d > r.vertex_concavity[v]) {
				r.vertex_concavity[v] = d;
				r.vertex_bridge[v]    = b;
			}
		}
	}

	// 7. Notches (reflex edges) and the most concave one. Ties go to the lexicographically smallest
	//    position, which does not depend on vertex order.
	for (int f = 0; f < nf; ++f)
		for (int k = 0; k < 3; ++k) {
			const int g = topo.neighbour[f][k];
			if (g < f || !is_reflex(m, topo, f, k)) continue;
			++r.notches;
			for (int v : {m.F[f][k], m.F[f][(k + 1) % 3]}) {
				const double c = r.vertex_concavity[v];
				bool better = c > r.max_concavity;
				if (!better && c == r.max_concavity && r.max_vertex >= 0 && c > 0) {
					const Vec3 &p = m.V[v], &q = m.V[r.max_vertex];
					better = std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
				}
				if (better || (r.max_vertex < 0 && c > 0)) {
					r.max_concavity = c;
					r.max_vertex    = v;
					r.max_bridge    = r.vertex_bridge[v];
				}
			}
		}
	return r;
}

} // namespace acd
