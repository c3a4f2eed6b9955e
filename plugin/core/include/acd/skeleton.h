// Skeleton extraction from the decomposition (the paper's Section 7): each part contributes the
// principal axis of its surface through its centroid, clipped to the part; a part whose axis leaves
// it or runs off-centre is split further across its axis (so the skeleton refines where the shape
// bends or twists); the skeletons of the two sides of every cut are joined through the centre of the
// cut's cross-section.
#pragma once

#include "acd/decompose.h"

namespace acd {

struct SkeletonOptions
{
	int    max_refinement = 3;     // splits of one part across its axis, at most (depth)
	double off_centre     = 0.25;  // refine when the axis chord's middle is this far from the centroid,
	                               // relative to the chord's length
};

struct Skeleton
{
	std::vector<Vec3>               V;
	std::vector<std::array<int, 2>> E;
	std::vector<int>                piece;   // per vertex: the piece it belongs to (joints: -1)
	int                             pieces = 0;
	int                             refined = 0;   // extra splits made for the skeleton
	int components() const;                        // connected components of the edge graph
};

Skeleton skeleton(const Decomposition& D, const SkeletonOptions& options = {});

} // namespace acd
