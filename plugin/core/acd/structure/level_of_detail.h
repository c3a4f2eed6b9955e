// Coarser levels read from a finished cut tree, nothing recomputed, and a subtree's solid rebuilt
// from its leaves.
#pragma once

#include "acd/decompose3/decompose.h"

#include <vector>

namespace acd {

// Level of detail from a finished tree, without recomputing: the nodes where the tree is cut when a
// piece may keep concavity up to `tau` (descend from the root while a node exceeds `tau`, holds a
// cavity that is not kept, or stands for several disjoint solids), or, with depth >= 0, the nodes at
// that depth (and leaves above it). Node ids in path order. By tau, a merged part replaces its leaves
// where the level keeps all of them (at the tree's own tau: the decomposition's parts).
std::vector<int> level_of_detail(const Decomposition& D, double tau, int depth = -1);

// The same by tau, and a node inside the tree is taken whole only if its hull is also certified within
// tau (hull_reach of the node rebuilt from the tree, to 1% of tau): the cuts never measured the hull
// of a node they split for a deeper notch, and a coarse part's hull may cover a hole its notches do not
// see (a ring's arc). `hull` gives the node's hull, or the rebuilt solid's when empty.
std::vector<int> level_of_detail_within(const Decomposition& D, double tau, const std::vector<TriMesh>& hull = {});

// The solid of node `id` rebuilt from the leaf meshes below it: the caps of the cuts inside the
// subtree are dropped, vertices welded, and the vertices that later cuts added on one side of a cap's
// rim are inserted into the other side's edges, so the result is closed again.
TriMesh rebuild_solid(const Decomposition& D, int id);

} // namespace acd
