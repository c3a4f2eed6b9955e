// Closing a surface welded from parts cut apart: rim edges split on one side only, and compaction.
#include "acd/solid/rims.h"
#include "acd/mesh/topology.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <utility>
#include <vector>

namespace acd {

namespace {

// The vertices of the edges used one way only, sorted.
std::vector<int> unmatched_ends(const std::vector<Tri>& F, const std::vector<char>& matched)
{
	std::vector<int> ends;
	for (size_t c = 0; c < matched.size(); ++c)
		if (!matched[c]) ends.push_back(F[c / 3][c % 3]), ends.push_back(F[c / 3][(c % 3 + 1) % 3]);
	std::sort(ends.begin(), ends.end());
	ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
	return ends;
}

// The rim vertices sorted along the axis they spread most on: those that can lie within eps of a
// segment are one range of them, handed out by id (the order a scan of all of them would meet them).
class RimIndex
{
public:
	RimIndex(const std::vector<Vec3>& V, const std::vector<int>& rim)
	{
		Eigen::AlignedBox3d box;
		for (int v : rim) box.extend(V[v]);
		if (!rim.empty()) (box.max() - box.min()).maxCoeff(&axis);
		for (int v : rim) along.push_back({V[v][axis], v});
		std::sort(along.begin(), along.end());
	}
	bool empty() const { return along.empty(); }
	// Every rim vertex within eps of segment ab (and others near it), by id.
	const std::vector<int>& near(const Vec3& a, const Vec3& b, double eps)
	{
		const double lo = std::min(a[axis], b[axis]), hi = std::max(a[axis], b[axis]);
		const double pad = eps + 1e-9 * (std::abs(lo) + std::abs(hi) + eps);   // and the test's rounding
		found.clear();
		for (auto it = std::lower_bound(along.begin(), along.end(), std::make_pair(lo - pad, -1));
		     it != along.end() && it->first <= hi + pad; ++it)
			found.push_back(it->second);
		std::sort(found.begin(), found.end());
		return found;
	}

private:
	int                                 axis = 0;
	std::vector<std::pair<double, int>> along;
	std::vector<int>                    found;
};

} // namespace

// Rims: a later cut on one side split a rim edge there; the other side's edge (b -> a, unmatched)
// gets the rim vertices lying on it, and its face is fanned out.
void close_rims(TriMesh& all, double eps)
{
	std::vector<char> matched = edge_uses(all.F).reversed;
	RimIndex          rims(all.V, unmatched_ends(all.F, matched));
	for (int pass = 0; pass < 8 && !rims.empty(); ++pass) {
		bool             changed = false;
		std::vector<Tri> faces;
		for (size_t f = 0; f < all.F.size(); ++f) {
			const Tri& t = all.F[f];
			int        k = 0, w = -1;
			for (; k < 3 && w < 0; ++k) {
				const int a = t[k], b = t[(k + 1) % 3];
				if (matched[3 * f + k]) continue;
				const Vec3 ab   = all.V[b] - all.V[a];
				double     best = 2;
				for (int v : rims.near(all.V[a], all.V[b], eps)) {
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
		matched = edge_uses(all.F).reversed;
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
