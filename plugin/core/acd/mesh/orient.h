// Consistent orientation of a surface's patches, for measures that need it (the winding number): game
// meshes and scans often carry patches whose faces are turned against their neighbours.
#pragma once

#include "acd/mesh/mesh.h"

namespace acd {

// Within each piece connected through edges of exactly two faces, turns the faces that disagree with
// their neighbours, keeping the orientation of the larger area; returns how many faces were turned.
// Pieces keep their own orientation; a non-orientable piece keeps what its first face's turn gives.
// Faces with a corner out of range or not finite are left as they are.
int orient_patches(TriMesh& m);

} // namespace acd
