#include "acd/mesh/orient.h"

#include <algorithm>
#include <map>

namespace acd {

int orient_patches(TriMesh& m)
{
	// Each undirected edge with its faces and whether each runs it from the lower vertex to the higher.
	const auto valid = [&](int f) { return finite_face(m, m.F[f]); };
	std::vector<std::array<int, 4>> uses;   // lo, hi, face, forward
	for (int f = 0; f < (int) m.F.size(); ++f)
		for (int k = 0; k < 3 && valid(f); ++k) {
			const int a = m.F[f][k], b = m.F[f][(k + 1) % 3];
			uses.push_back({std::min(a, b), std::max(a, b), f, a < b});
		}
	std::sort(uses.begin(), uses.end());
	std::vector<std::vector<std::pair<int, bool>>> next(m.F.size());   // neighbour, agrees
	for (size_t i = 0; i < uses.size();) {
		size_t j = i;
		while (j < uses.size() && uses[j][0] == uses[i][0] && uses[j][1] == uses[i][1]) ++j;
		if (j - i == 2) {
			const bool agree = uses[i][3] != uses[i + 1][3];   // consistent faces run a shared edge both ways
			next[uses[i][2]].push_back({uses[i + 1][2], agree});
			next[uses[i + 1][2]].push_back({uses[i][2], agree});
		}
		i = j;
	}
	const auto area = [&](int f) {
		if (!valid(f)) return 0.0;
		return (m.V[m.F[f][1]] - m.V[m.F[f][0]]).cross(m.V[m.F[f][2]] - m.V[m.F[f][0]]).norm();
	};
	std::vector<int> turn(m.F.size(), -1);
	int              turned = 0;
	for (int s = 0; s < (int) m.F.size(); ++s) {
		if (turn[s] >= 0) continue;
		std::vector<int> piece = {s};
		turn[s]                = 0;
		double weight[2]       = {0, 0};
		for (size_t i = 0; i < piece.size(); ++i) {
			const int f = piece[i];
			weight[turn[f]] += area(f);
			for (auto [g, agree] : next[f])
				if (turn[g] < 0) turn[g] = agree ? turn[f] : 1 - turn[f], piece.push_back(g);
		}
		const int flip = weight[1] > weight[0] ? 0 : 1;   // the faces of the smaller area turn
		for (int f : piece)
			if (turn[f] == flip) std::swap(m.F[f][1], m.F[f][2]), ++turned;
	}
	return turned;
}

} // namespace acd
