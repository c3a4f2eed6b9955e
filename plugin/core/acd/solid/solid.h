// A closed, oriented, edge-manifold solid made from a triangle mesh, or a clear error saying why not.
#pragma once

#include "acd/mesh/mesh.h"

#include <utility>
#include <vector>

namespace acd {

// A validated solid: compact, finite, closed, 2-manifold along edges, consistently and outward
// oriented. Vertices shared by several fans (non-manifold vertices) are split into one copy per fan,
// so every later step can rely on edge-manifoldness. `source_vertex[i]` is the input index of V[i].
struct Solid
{
	TriMesh          mesh;
	std::vector<int> source_vertex;
	int              shells = 0;            // connected components (by edges)
	int              split_vertices = 0;    // non-manifold vertices that were split
	int              unreferenced_vertices = 0;
	bool             flipped = false;       // the input (or some shell) was inside out and has been turned
	int              reoriented_shells = 0; // shells whose orientation disagreed with their nesting
	int              cavities = 0;          // shells nested inside another an odd number of times
	long             self_intersections = 0;   // pairs of faces crossing away from shared corners
	std::vector<std::pair<int, int>> crossing_faces;   // those pairs (mesh.F indices); their count is the above
	double           volume = 0;
};

// Throws Error(InvalidInput) naming the first problem found (with its code and count). Without
// `crossings`, a solid of one shell is not searched for crossing faces (self_intersections -1): a
// caller that may refuse it on other grounds first searches later (self_crossings). A solid of several
// shells is always searched, as their nesting depends on it.
Solid make_solid(const TriMesh& input, bool crossings = true);

// The pairs of faces that cross away from shared corners (corners within 1e-9 `diag` count as shared).
std::vector<std::pair<int, int>> self_crossings(const TriMesh& m, double diag);

// The solid's crossing pairs and their count found (after make_solid without them).
void find_crossings(Solid& s);

// The solid's crossing face pairs but for those that one of `cuts` separates (each face on its own side,
// a face lying in the plane on its solid's side): parts glued along a cut only touch there (their rims
// met a rounding error apart, or they meet along an edge), which is no fold. `eps`: the planes' width.
long crossings_off_cuts(const Solid& s, const std::vector<Plane>& cuts, double eps);

} // namespace acd
