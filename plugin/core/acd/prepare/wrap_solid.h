// Automatic preprocessing: the input as given when it is a valid solid, otherwise the least alpha wrap
// that is solid rather than a hollow skin (or the first wrap, when the input encloses no solid).
#pragma once

#include "acd/mesh/mesh.h"
#include "acd/solid/solid.h"

#include <optional>
#include <string>

namespace acd {

struct WrapSolidResult
{
	TriMesh     mesh;               // the wrap (or the input, welded if `welded` > 0, when not wrapped)
	bool        wrapped = false;
	int         welded  = 0;        // vertices merged into another (cracks closed without a wrap)
	double      alpha   = 0;        // the alpha of the wrap kept (model units)
	double      inside  = 1;        // share of the input's interior samples inside the wrap kept
	int         tries   = 0;        // wraps computed (the last one is not always the one kept)
	std::string reason;             // why the input was not used as given
	int         reason_code  = 0;   // and that error's Error::Code and count
	long        reason_count = 0;
	std::optional<Solid> solid;     // make_solid(mesh), when not wrapped: no need to validate it again
};

// Generalized winding number of the surface (V, F) at each point: about 1 inside a closed outward
// surface, 0 outside, and still close to that for a surface with small holes.
std::vector<double> winding_numbers(const TriMesh& surface, const std::vector<Vec3>& points);

// An open mesh wrapped with an alpha smaller than its holes is a thin skin hugging both sides of the
// surface (the wrap slipped inside). Wraps with alpha, 2 alpha, ... up to max_alpha, and keeps the first
// that holds at least `min_inside` of the points the input's winding number places inside; when none
// does, the input is an open shell and the first wrap, its skin, is kept. The input is returned as
// given when make_solid accepts it, and welded (1e-5 of its size) when that is all it takes.
WrapSolidResult wrap_solid(const TriMesh& input, double alpha, double offset, double max_alpha,
                           double min_inside = 0.5);

} // namespace acd
