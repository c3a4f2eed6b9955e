// Preprocessing that makes dirty input decomposable: open, non-manifold, self-intersecting meshes,
// triangle soups and point clouds become one closed, 2-manifold, outward surface.
#pragma once

#include "acd/mesh/mesh.h"

namespace acd {

// CGAL's 3D alpha wrapping of the finite part of `input` (faces with a non-finite corner dropped;
// no faces: the points are wrapped). The result lies outside the input at a distance of about
// `offset`; cavities and gaps narrower than about `alpha` are closed. Both are model lengths > 0.
// Throws Error(InvalidInput) when nothing finite is left, Error(InvalidOption) for bad lengths or a
// wrap so fine that it would not fit in memory.
TriMesh alpha_wrap(const TriMesh& input, double alpha, double offset);

} // namespace acd
