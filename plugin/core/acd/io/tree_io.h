// The cut tree as JSON, the one format the plugin writes (tree_file) and reads back (level of detail);
// its fields are documented in docs/tree-format.md. Every file carries "schema": kTreeSchema.
#pragma once

#include "acd/decompose3/decompose.h"
#include "acd/polygon/polygon.h"
#include "acd/structure/collision_hulls.h"

#include <string>
#include <vector>

namespace acd {

constexpr int kTreeSchema = 1;

// A 3D tree; with `geometry`, each node's convex hull and each leaf's mesh too (what level_of_detail
// and rebuild_solid need to serve coarser levels later without recomputing). With `hulls`, each collision
// hull's counts, reach beyond the exact hull and thickness under "hulls" (docs/tree-format.md).
std::string tree_to_json(const Decomposition& D, bool geometry = false, const CollisionHulls* hulls = nullptr);

// A tree written by tree_to_json(D, true), back into the core's structure: links, planes, leaf meshes;
// `hulls` (if given) gets each node's stored hull by node id (empty where none was stored). Throws
// Error(InvalidInput) naming what is wrong with the file.
Decomposition tree_from_json(const std::string& text, std::vector<TriMesh>* hulls = nullptr);

// The 2D trees of a polygon decomposition, one per polygon: {"schema", "dimension": 2, "polygons": [...]}.
std::string polygon_trees_to_json(const std::vector<Decomposition2>& trees);

} // namespace acd
