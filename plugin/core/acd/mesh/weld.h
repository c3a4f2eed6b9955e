// Closing hairline cracks: vertices that coincide within a tolerance become one.
#pragma once

#include "acd/mesh/mesh.h"

namespace acd {

// Vertices within `eps` of an earlier vertex merged into it, faces that collapse or repeat dropped:
// STL and CAD exports leave unshared corners and hairline cracks that open an otherwise closed solid.
TriMesh weld(const TriMesh& input, double eps, int* merged = nullptr);

} // namespace acd
