// What an open surface encloses, as a surface: the level set |w| = 1/2 of its generalized winding
// number, by marching tetrahedra on a grid, with the vertices near the input moved onto it. Where the
// input is closed the level set is the input itself; across an opening it is a cap that continues the
// surface. The caps are the level set's faces not moved onto the input entirely: wrapped together with
// the input, they keep the wrap from slipping inside.
#pragma once

#include "acd/mesh/mesh.h"
#include "acd/mesh/nearest.h"
#include "acd/mesh/winding_number.h"

namespace acd {

struct WindingCaps
{
	TriMesh mesh;            // the caps, a triangle soup (the wrap needs no orientation)
	double  spacing   = 0;   // the grid's, model units
	double  cap_share = 0;   // share of its area away from the input: the openings it spans
	double  reach     = 0;   // the largest distance from a vertex of the caps to the input
};

// The grid holds at most `max_points` points (its spacing grows beyond `spacing` to fit).
WindingCaps winding_caps(const TriMesh& input, const WindingNumber& wn, const NearestOnSurface& near,
                         double spacing, size_t max_points = 3000000);

} // namespace acd
