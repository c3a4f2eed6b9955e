#include "acd/mesh/topology.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <unordered_set>

namespace acd {

std::vector<int> reflex_chain(const TriMesh& m, const Topology& t, int v, const Vec3& dir, double min_cos)
{
	std::vector<int>        out{v};
	std::unordered_set<int> seen{v};
	bool                    closed = false;
	// One way from v, then the other; a closed loop ends the walk where it started.
	for (const double way : {1.0, -1.0}) {
		int  prev = -1, cur = v;
		Vec3 d    = way * dir;
		std::vector<int> side;
		while (!closed) {
			int    next = -1;
			double cmax = min_cos;
			for (int i = t.adj_start[cur]; i < t.adj_start[cur + 1]; ++i) {
				const int w = t.adj[i], c = t.adj_corner[i];
				if (w == prev || !is_reflex(m, t, c / 3, c % 3)) continue;
				const Vec3   e  = m.V[w] - m.V[cur];
				const double en = e.norm();
				if (!(en > 0)) continue;
				const double cs = e.dot(d) / en;
				if (cs > cmax) cmax = cs, next = w;
			}
			if (next < 0) break;
			if (next == v) closed = true;
			if (closed || !seen.insert(next).second) break;
			d    = (m.V[next] - m.V[cur]).normalized();
			prev = cur;
			cur  = next;
			side.push_back(cur);
		}
		if (way > 0) std::reverse(side.begin(), side.end());
		out.insert(way > 0 ? out.begin() : out.end(), side.begin(), side.end());
	}
	return out;
}

std::optional<Vec3> chain_plane_normal(const std::vector<Vec3>& pts)
{
	if (pts.size() < 4) return std::nullopt;
	Vec3 c = Vec3::Zero();
	for (const Vec3& p : pts) c += p;
	c /= (double) pts.size();
	Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
	for (const Vec3& p : pts) cov += (p - c) * (p - c).transpose();
	const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov / (double) pts.size());
	const Eigen::Vector3d l = es.eigenvalues().cwiseMax(0.0);   // ascending
	// A straight chain (a slot's edge) spans no plane; a chain off its plane (a wrapped surface's
	// ragged crease) is no rim.
	if (!(std::sqrt(l[1]) >= 0.1 * std::sqrt(l[2]))) return std::nullopt;
	const Vec3 n     = es.eigenvectors().col(0);
	double     worst = 0, size = 0;
	for (const Vec3& p : pts) {
		worst = std::max(worst, std::abs(n.dot(p - c)));
		size  = std::max(size, (p - c).norm());
	}
	if (!(worst <= 1e-3 * size)) return std::nullopt;
	return n;
}

} // namespace acd
