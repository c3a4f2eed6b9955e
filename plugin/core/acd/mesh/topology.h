// Face and vertex adjacency of a closed, edge-manifold triangle mesh.
#pragma once

#include "acd/mesh/mesh.h"

#include <optional>

namespace acd {

// Each corner's edge (corner 3f+k runs from F[f][k] to F[f][k+1]) found with the other uses of its
// undirected edge by sorting one array of keys: no hash map and no search per edge, which keeps the
// checks of a mesh with millions of faces to a fraction of a second. Any faces, closed or not.
struct EdgeUses
{
	long              boundary = 0, nonmanifold = 0, misoriented = 0;   // undirected edges used once, > twice, twice one way
	std::vector<int>  mate;       // per corner, the corner using its edge the other way (-1: none, or not one)
	std::vector<char> reversed;   // per corner, some corner uses its edge the other way (an a -> a edge is its own)
};
EdgeUses edge_uses(const std::vector<Tri>& F);

struct Topology
{
	// neighbour[f][k]: the face across edge (F[f][k], F[f][(k+1)%3]); -1 if none.
	std::vector<std::array<int, 3>> neighbour;
	// CSR vertex -> neighbouring vertices; adj_corner[i] = 3f+k of the face f whose edge k runs
	// from the vertex to adj[i] (each directed edge of a closed manifold is in exactly one face).
	std::vector<int> adj_start, adj, adj_corner;
	// Heights below this (1e-9 of the mesh's extent) are rounding: a dihedral that close to flat
	// is neither reflex nor convex.
	double flat = 0;

	explicit Topology(const TriMesh& m);
	template <class Fn> void for_each_neighbour(int v, Fn fn) const
	{
		for (int i = adj_start[v]; i < adj_start[v + 1]; ++i) fn(adj[i]);
	}
	// 3f+k of the directed edge a->b, or -1 if a and b are not neighbours.
	int corner(int a, int b) const
	{
		for (int i = adj_start[a]; i < adj_start[a + 1]; ++i)
			if (adj[i] == b) return adj_corner[i];
		return -1;
	}
};

// Is the edge (F[f][k], F[f][k+1]) reflex, i.e. is its dihedral angle, measured inside the solid,
// above 180 degrees? Each face's far vertex must rise above the other face's plane by more than
// `flat`: an angle threshold alone lets the noisy normals of tiny cut triangles decide.
bool is_reflex(const TriMesh& m, const Topology& t, int f, int k);

// The chain of reflex edges through vertex v, walked both ways starting along dir: at each vertex
// the reflex edge that turns least, if it turns by less than acos(min_cos). A CAD rim (a groove's
// or a step's ring, a pocket's floor edge) is such a chain. Its vertices in order along it.
std::vector<int> reflex_chain(const TriMesh& m, const Topology& t, int v, const Vec3& dir, double min_cos);

// The normal of the plane a chain of points lies in, if it spans one (not a straight line) and
// keeps to it within 1e-3 of its size.
std::optional<Vec3> chain_plane_normal(const std::vector<Vec3>& pts);

} // namespace acd
