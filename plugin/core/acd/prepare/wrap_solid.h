// Automatic preprocessing: the input as given when it is a valid solid, otherwise the least alpha wrap
// that is solid rather than a hollow skin (or the first wrap, when the input encloses no solid).
#pragma once

#include "acd/mesh/mesh.h"
#include "acd/mesh/nearest.h"
#include "acd/solid/solid.h"

#include <optional>
#include <string>
#include <utility>

namespace acd {

struct WrapSolidResult
{
	TriMesh     mesh;               // the wrap (or the input, welded if `welded` > 0, when not wrapped)
	bool        wrapped = false;
	int         welded  = 0;        // vertices merged into another (cracks closed without a wrap)
	double      alpha   = 0;        // the alpha of the wrap kept (model units)
	double      inside  = 1;        // share of the input's interior samples inside the wrap kept
	int         tries   = 0;        // wraps computed (the last one is not always the one kept)
	int         filled  = 0;        // holes filled in the input itself (not wrapped)
	int         on_planes = 0;      // of them, closed on the planes their rims run on (plane_fill.h)
	bool        capped  = false;    // the openings were closed along the winding number's level set
	bool        skin    = false;    // the input encloses no solid: the wrap is a thin skin about it
	double      cap_share = 0;      // share of the level set's area that spans openings
	double      coarse_cell = 0;    // a big input is wrapped with its vertices this close merged (0: none)
	double      to_input   = 0;     // largest distance from the wrap's surface to the input
	double      from_input = 0;     // and from the input's vertices to the wrap (model units)
	std::string reason;             // why the input was not used as given
	int         reason_code  = 0;   // and that error's Error::Code and count
	long        reason_count = 0;
	std::optional<Solid> solid;     // make_solid(mesh), when not wrapped: no need to validate it again
};

// Generalized winding number of the surface (V, F) at each point: about 1 inside a closed outward
// surface, 0 outside, and still close to that for a surface with small holes.
std::vector<double> winding_numbers(const TriMesh& surface, const std::vector<Vec3>& points);

// An open mesh wrapped with an alpha smaller than its holes is a thin skin hugging both sides of the
// surface (the wrap slipped inside). The caps of the input's winding-number level set |w| = 1/2
// (winding_caps, on a grid of alpha / 2) tell its openings. Where a cap lies farther than alpha from the
// input, the input is wrapped together with the caps, which close the openings along the surface's
// continuation; otherwise the plain wrap at alpha is made, and the caps are added only if it holds less
// than `min_inside` of the points the winding number places inside. When the caps span more than
// `max_cap_share` of the level set, or reach farther than max_alpha from the input (openings wider than
// the coarsest wrap would close), the input is an open shell (a bowl, a tube, a helmet) and the plain
// wrap, its skin, is kept; so it is when too few points are inside to judge (a sheet, a point cloud).
// Should a capped wrap not hold the interior, wraps with 2 alpha, 4 alpha, ... up to max_alpha are
// tried. The input is returned as given when make_solid accepts it, and welded (1e-5 of its size) when
// that is all it takes. Before any wrap, an input with openings that is no open shell has its holes
// filled (fill_holes, with `fill`): kept, not wrapped, when that makes a valid solid that does
// not cross itself, for it is the input itself with patches that continue its surface.
WrapSolidResult wrap_solid(const TriMesh& input, double alpha, double offset, double max_alpha,
                           double min_inside = 0.5, double max_cap_share = 0.25, bool fill = true);

// How far a wrap lies from its input, both ways: the largest distance from the wrap's surface (its
// vertices, edge midpoints and face centroids) to the input (near: the input's tree), and from the input's
// finite vertices that a face uses to the wrap.
std::pair<double, double> wrap_distances(const TriMesh& wrap, const TriMesh& input, const NearestOnSurface& near);

} // namespace acd
