#include "acd/mesh/weld.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>
#include <vector>

namespace acd {

namespace {

// The vertices kept (into out.V) and where each input vertex went (`to`): each one merges with the
// first kept vertex within eps found in the 27 cells around it, else it is kept. Returns the merges.
int weld_vertices(const TriMesh& in, double eps, TriMesh& out, std::vector<int>& to)
{
	struct CellHash
	{
		size_t operator()(const std::array<long long, 3>& c) const
		{
			return std::hash<long long>()(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
		}
	};
	// Each cell's kept vertices in the order they were kept: a chain through `next`, (first, last) by cell.
	std::unordered_map<std::array<long long, 3>, std::pair<int, int>, CellHash> grid;
	grid.reserve(in.V.size());
	std::vector<int> next;
	next.reserve(in.V.size());
	out.V.reserve(in.V.size());
	to.assign(in.V.size(), -1);
	int n = 0;
	for (size_t i = 0; i < in.V.size(); ++i) {
		const Vec3& p = in.V[i];
		if (!p.allFinite()) {   // kept apart: make_solid names them
			to[i] = (int) out.V.size();
			out.V.push_back(p);
			next.push_back(-1);
			continue;
		}
		const std::array<long long, 3> c{(long long) std::floor(p.x() / eps), (long long) std::floor(p.y() / eps),
		                                 (long long) std::floor(p.z() / eps)};
		for (int dx = -1; dx <= 1 && to[i] < 0; ++dx)
			for (int dy = -1; dy <= 1 && to[i] < 0; ++dy)
				for (int dz = -1; dz <= 1 && to[i] < 0; ++dz) {
					auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
					if (it == grid.end()) continue;
					for (int j = it->second.first; j >= 0; j = next[j])
						if ((out.V[j] - p).norm() <= eps) { to[i] = j; ++n; break; }
				}
		if (to[i] < 0) {
			to[i] = (int) out.V.size();
			const auto [it, fresh] = grid.try_emplace(c, to[i], to[i]);
			if (!fresh) next[it->second.second] = to[i], it->second.second = to[i];
			out.V.push_back(p);
			next.push_back(-1);
		}
	}
	return n;
}

} // namespace

TriMesh weld(const TriMesh& in, double eps, int* merged)
{
	TriMesh          out;
	std::vector<int> to;
	const int        n = weld_vertices(in, eps, out, to);
	for (const Tri& t : in.F) {
		bool ok = true;
		for (int v : t) ok = ok && v >= 0 && v < (int) in.V.size();
		if (!ok) { out.F.push_back(t); continue; }   // left for make_solid to name
		const Tri w{to[t[0]], to[t[1]], to[t[2]]};
		if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) continue;
		out.F.push_back(w);
	}
	// Faces the welding made identical (same corners, same turn) are one face.
	std::vector<std::pair<std::array<int, 3>, int>> keys;
	for (int f = 0; f < (int) out.F.size(); ++f) {
		Tri t = out.F[f];
		std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
		keys.push_back({{t[0], t[1], t[2]}, f});
	}
	std::sort(keys.begin(), keys.end());
	std::vector<char> drop(out.F.size(), 0);
	for (size_t k = 1; k < keys.size(); ++k) drop[keys[k].second] = keys[k].first == keys[k - 1].first;
	std::vector<Tri> kept;
	for (size_t f = 0; f < out.F.size(); ++f)
		if (!drop[f]) kept.push_back(out.F[f]);
	out.F = std::move(kept);
	if (merged) *merged = n;
	return out;
}

} // namespace acd
