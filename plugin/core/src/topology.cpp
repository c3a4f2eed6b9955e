#include "acd/topology.h"

#include <unordered_map>

namespace acd {

Topology::Topology(const TriMesh& m)
{
	const int nf = (int) m.F.size(), nv = (int) m.V.size();
	std::unordered_map<long long, int> half;   // directed edge -> face
	half.reserve(nf * 3);
	auto key = [](int a, int b) { return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b); };
	for (int f = 0; f < nf; ++f)
		for (int k = 0; k < 3; ++k) half[key(m.F[f][k], m.F[f][(k + 1) % 3])] = f;
	neighbour.assign(nf, {-1, -1, -1});
	adj_start.assign(nv + 1, 0);
	for (int f = 0; f < nf; ++f)
		for (int k = 0; k < 3; ++k) {
			auto it = half.find(key(m.F[f][(k + 1) % 3], m.F[f][k]));
			if (it != half.end()) neighbour[f][k] = it->second;
			++adj_start[m.F[f][k] + 1];
		}
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
	const Vec3 n  = (m.V[b] - m.V[a]).cross(m.V[c] - m.V[a]);
	const Vec3 ad = m.V[d] - m.V[a];
	// d above the plane of f (on its outer side) means the solid turns inward: a reflex edge.
	// The relative threshold keeps numerically flat edges out.
	return n.dot(ad) > 1e-10 * n.norm() * ad.norm();
}

} // namespace acd
