// Simplification by the union of the parts' convex hulls (the paper's Figure 18), and the measure
// that says how faithful it is.
#pragma once

#include "acd/mesh/mesh.h"

namespace acd {

// The hulls merged into one mesh: their disjoint union (`boolean` false: overlapping shells, fine for
// display and collision), or the true boolean union by CGAL's corefinement with exact constructions
// (`boolean` true: one closed surface). Throws Error(Internal) if the boolean union fails.
TriMesh merge_hulls(const std::vector<TriMesh>& hulls, bool boolean);

// Volume IoU between a closed mesh and the union of convex hulls, by `samples` Monte Carlo points in
// the common bounding box (deterministic for a seed); `stderr_out` gets its standard error.
double volume_iou(const TriMesh& mesh, const std::vector<TriMesh>& hulls, int samples, unsigned seed = 1,
                  double* stderr_out = nullptr);

} // namespace acd
