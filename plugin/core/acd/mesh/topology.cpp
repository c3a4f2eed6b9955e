#include "acd/mesh/topology.h"
#include "acd/mesh/measures.h"
#include "acd/mesh/parallel.h"

namespace acd {

EdgeUses edge_uses(const std::vector<Tri>& F)
{
	using Key = unsigned long long;
	std::vector<std::pair<Key, int>> e;
	e.reserve(F.size() * 3);
	for (int f = 0; f < (int) F.size(); ++f)
		for (int k = 0; k < 3; ++k) {
			const unsigned a = (unsigned) F[f][k], b = (unsigned) F[f][(k + 1) % 3];
			e.push_back({(Key) std::min(a, b) << 32 | std::max(a, b), 3 * f + k});
		}
	sort_halves(e.begin(), e.end());   // keys with their corner: no two equal
	EdgeUses u;
	u.mate.assign(e.size(), -1);
	u.reversed.assign(e.size(), 0);
	const auto from = [&](int c) { return F[c / 3][c % 3]; };
	for (size_t i = 0, j; i < e.size(); i = j) {
		bool      way[2] = {false, false};   // some use runs from the lower end, from the higher
		const int low    = (int) (e[i].first >> 32);
		for (j = i; j < e.size() && e[j].first == e[i].first; ++j) way[from(e[j].second) != low] = true;
		const bool loop = low == (int) (e[i].first & 0xffffffffu);
		for (size_t k = i; k < j; ++k) u.reversed[e[k].second] = loop || way[from(e[k].second) == low];
		if (j - i == 1) ++u.boundary;
		else if (j - i > 2) ++u.nonmanifold;
		else if (from(e[i].second) == from(e[i + 1].second)) ++u.misoriented;
		else u.mate[e[i].second] = e[i + 1].second, u.mate[e[i + 1].second] = e[i].second;
	}
	return u;
}

Topology::Topology(const TriMesh& m)
{
	const int nf = (int) m.F.size(), nv = (int) m.V.size();
	flat = 1e-9 * extent(m.V);
	adj_start.assign(nv + 1, 0);
	for (const Tri& t : m.F)
		for (int v : t) ++adj_start[v + 1];
	for (int v = 0; v < nv; ++v) adj_start[v + 1] += adj_start[v];
	adj.resize(adj_start[nv]);
	adj_corner.resize(adj_start[nv]);
	std::vector<int> fill(adj_start.begin(), adj_start.end() - 1);
	// Each undirected edge of a closed manifold appears once in each direction.
	for (int f = 0; f < nf; ++f)
		for (int k = 0; k < 3; ++k) {
			const int i   = fill[m.F[f][k]]++;
			adj[i]        = m.F[f][(k + 1) % 3];
			adj_corner[i] = 3 * f + k;
		}
	// The face across edge a->b holds b->a: found in b's short list, no hashing.
	neighbour.assign(nf, {-1, -1, -1});
	for (int f = 0; f < nf; ++f)
		for (int k = 0; k < 3; ++k) {
			const int c = corner(m.F[f][(k + 1) % 3], m.F[f][k]);
			if (c >= 0) neighbour[f][k] = c / 3;
		}
}

bool is_reflex(const TriMesh& m, const Topology& t, int f, int k)
{
	const int g = t.neighbour[f][k];
	if (g < 0) return false;
	const int a = m.F[f][k], b = m.F[f][(k + 1) % 3], c = m.F[f][(k + 2) % 3];
	int       d = -1;
	for (int j = 0; j < 3; ++j)
		if (m.F[g][j] != a && m.F[g][j] != b) d = m.F[g][j];
	if (d < 0) return false;
	auto rise = [&](int p, int q, int r, int x) {   // height of x above the plane of (p, q, r)
		const Vec3   n  = (m.V[q] - m.V[p]).cross(m.V[r] - m.V[p]);
		const double nn = n.norm();
		return nn > 0 ? n.dot(m.V[x] - m.V[p]) / nn : 0.0;
	};
	return rise(a, b, c, d) > t.flat && rise(b, a, d, c) > t.flat;
}

} // namespace acd
