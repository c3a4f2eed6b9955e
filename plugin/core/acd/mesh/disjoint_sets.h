// Union-find over 0..n-1 with path halving (faces into shells, hull triangles into facets, cap faces
// into cross-sections).
#pragma once

#include <numeric>
#include <vector>

namespace acd {

struct DisjointSets
{
	std::vector<int> parent;
	explicit DisjointSets(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
	int root(int x)
	{
		while (parent[x] != x) x = parent[x] = parent[parent[x]];
		return x;
	}
	void unite(int a, int b) { parent[root(a)] = root(b); }
};

} // namespace acd
