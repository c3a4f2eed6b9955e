// Closing a surface welded from parts cut apart: rim edges split on one side only, and compaction.
#include "acd/solid/rims.h"

#include <set>

namespace acd {

namespace {

std::set<std::pair<int, int>> directed_edges(const TriMesh& m)
{
	std::set<std::pair<int, int>> directed;
	for (const Tri& t : m.F)
		for (int k = 0; k < 3; ++k) directed.insert({t[k], t[(k + 1) % 3]});
	return directed;
}

} // namespace

// Rims: a later cut on one side split a rim edge there; the other side's edge (b -> a, unmatched)
// gets the rim vertices lying on it, and its face is fanned out.
void close_rims(TriMesh& all, double eps)
{
	std::set<std::pair<int, int>> directed = directed_edges(all);
	std::set<int>                 rim;
	for (const auto& [a, b] : directed)
		if (!directed.count({b, a})) rim.insert(a), rim.insert(b);
	std::vector<int> rim_v(rim.begin(), rim.end());
	for (int pass = 0; pass < 8 && !rim_v.empty(); ++pass) {
		bool             changed = false;
		std::vector<Tri> faces;
		for (const Tri& t : all.F) {
			int k = 0, w = -1;
			for (; k < 3 && w < 0; ++k) {
				const int a = t[k], b = t[(k + 1) % 3];
				if (directed.count({b, a})) continue;
				const Vec3 ab   = all.V[b] - all.V[a];
				double     best = 2;
				for (int v : rim_v) {
					if (v == a || v == b || v == t[(k + 2) % 3]) continue;
					const double s = (all.V[v] - all.V[a]).dot(ab) / ab.squaredNorm();
					if (s <= 0 || s >= 1 || (all.V[a] + s * ab - all.V[v]).norm() > eps) continue;
					if (s < best) best = s, w = v;   // the nearest to a first; later passes do the rest
				}
			}
			if (w < 0) {
				faces.push_back(t);
				continue;
			}
			--k;   // edge k (a -> b) gets w: (a, w, c) and (w, b, c)
			const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
			faces.push_back({a, w, c});
			faces.push_back({w, b, c});
			changed = true;
		}
		all.F.swap(faces);
		if (!changed) break;
		directed = directed_edges(all);
	}
}

// The vertices the faces use, renumbered in order of first use.
TriMesh compacted(const TriMesh& all)
{
	TriMesh          out;
	std::vector<int> id_new(all.V.size(), -1);
	for (const Tri& t : all.F) {
		Tri u;
		for (int k = 0; k < 3; ++k) {
			int& i = id_new[t[k]];
			if (i < 0) {
				i = (int) out.V.size();
				out.V.push_back(all.V[t[k]]);
			}
			u[k] = i;
		}
		out.F.push_back(u);
	}
	return out;
}

} // namespace acd
