// Two solids that touch along cut planes glued into one solid: where their faces on a plane overlap,
// both are dropped; what is left of those faces on either side stays as the union's boundary.
#pragma once

#include "acd/mesh.h"

#include <vector>

namespace acd {

// `a` and `b` are closed solids on opposite sides of each plane where they touch (parts of one solid
// cut by those planes, their shared vertices bit-identical). Faces within `eps` of a plane are cut
// in the plane's 2D frame (exactly): each keeps what the other solid's opposite faces do not cover;
// the seams are closed (rims.h) and the slivers a rounding error wide that the two sides' seams leave
// collapsed. The result is only a candidate: its caller validates it (make_solid, volume).
TriMesh glue(const TriMesh& a, const TriMesh& b, const std::vector<Plane>& planes, double eps);

} // namespace acd
