// Skeleton extraction from the decomposition tree (the paper's Section 7, Figure 14), top down: a
// node's skeleton is the principal axis of its convex hull through the hull's centroid, clipped to
// the node's solid. If that axis leaves the solid (the chord inside spans less than min_cover of the
// hull's) or runs off-centre, the node's cut splits it and the two sides' skeletons are joined through
// the centre of the cut's cross-section; a leaf that is still not good is split across its axis (so
// the skeleton refines where the shape bends or twists). Coarse nodes with a good axis stay whole.
#pragma once

#include "acd/decompose3/decompose.h"

namespace acd {

struct SkeletonOptions
{
	int    max_refinement = 3;     // splits of one part across its axis, at most (depth)
	double off_centre     = 0.2;   // refine when the axis chord's middle is this far from the centroid,
	                               // relative to the chord's length; or, at stations along the chord,
	                               // this far from the middle of the solid's width across it, relative
	                               // to that width
	double min_cover      = 0.8;   // refine when the chord inside the piece spans less than this much
	                               // of the axis across the piece's hull (the axis leaves the piece)
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
