// Closing a surface welded from parts that plane cuts made (internal header of the core).
#pragma once

#include "acd/mesh.h"

namespace acd {

// T-junctions: an edge used in one direction only (its other side was split by a later cut) gets
// the unmatched edges' end vertices lying on it within `eps`, and its face is fanned out.
void close_rims(TriMesh& all, double eps);

// The vertices the faces use, renumbered in order of first use.
TriMesh compacted(const TriMesh& all);

} // namespace acd
