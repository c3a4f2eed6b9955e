// Two solids that touch along cut planes glued into one solid: where their faces on a plane overlap,
// both are dropped; what is left of those faces on either side stays as the union's boundary.
#pragma once

#include "acd/mesh/mesh.h"

#include <vector>

namespace acd {

// `a` and `b` are closed solids on opposite sides of each plane where they touch (parts of one solid
// cut by those planes, their shared vertices bit-identical). On each plane, the faces within `eps` of
// it are replaced by a constrained triangulation of the boundaries of each side's faces there, those
// turned up and those turned down apart (exact, in the plane's frame; of all their edges where such a
// class of faces is not one region) restricted to where exactly one side covers it: the two sides'
// opposite faces cancel where they overlap. Plane vertices within `eps` of each other are one. The
// seams are closed (rims.h) and the slivers that rounding leaves collapsed. The result is only a
// candidate: its caller validates it (make_solid, volume).
TriMesh glue(const TriMesh& a, const TriMesh& b, const std::vector<Plane>& planes, double eps);

} // namespace acd
