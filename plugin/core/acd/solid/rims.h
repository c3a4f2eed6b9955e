// Closing a surface welded from parts that plane cuts made (internal header of the core).
#pragma once

#include "acd/mesh/mesh.h"

#include <array>
#include <map>

namespace acd {

// Parts welded where a cut left the same vertex on both sides of its cap (bit-identical copies).
class ExactWeld
{
public:
	explicit ExactWeld(std::vector<Vec3>& V) : V(V) {}
	// m's vertices added to V, each position once; m's vertex -> its index in V.
	std::vector<int> add(const TriMesh& m)
	{
		std::vector<int> id(m.V.size());
		for (size_t v = 0; v < m.V.size(); ++v) {
			auto [it, fresh] = at.emplace(std::array<double, 3>{m.V[v].x(), m.V[v].y(), m.V[v].z()}, (int) V.size());
			if (fresh) V.push_back(m.V[v]);
			id[v] = it->second;
		}
		return id;
	}

private:
	std::vector<Vec3>&                   V;
	std::map<std::array<double, 3>, int> at;
};

// T-junctions: an edge used in one direction only (its other side was split by a later cut) gets
// the unmatched edges' end vertices lying on it within `eps`, and its face is fanned out.
void close_rims(TriMesh& all, double eps);

// The vertices the faces use, renumbered in order of first use.
TriMesh compacted(const TriMesh& all);

} // namespace acd
