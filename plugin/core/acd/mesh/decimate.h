// Edge-collapse decimation of a closed mesh for a coarse copy to search on: each collapse keeps the
// surface closed and edge-manifold (the link condition), turns no face over, and places the kept
// vertex where the area-weighted quadric of the faces it stands for is least.
#pragma once

#include "acd/mesh/mesh.h"

namespace acd {

struct Decimated
{
	TriMesh mesh;
	int     passes = 0;   // rounds of independent collapses
};

// Collapses the cheapest edges, in rounds of collapses whose neighbourhoods do not overlap, until at
// most `target_faces` faces are left or no edge's root-mean-square distance to the planes it stands
// for stays within `max_error` (model units). `m` must be closed, edge-manifold and oriented
// (make_solid's). The same surface gives the same output in any order of its vertices and faces, and
// in any pose where its principal axes are its own: it is decimated in that frame on a grid of about
// 1e-8 of its size, its vertices listed by position, the rounds ordered by cost, then by those ids.
Decimated decimate(const TriMesh& m, int target_faces, double max_error);

} // namespace acd
