// The one preprocessing entry: a mesh as the user gives it becomes the solid the decomposition cuts,
// as given, welded or alpha wrapped, with a record of what was done. A new mode is a value of the enum,
// a row of preprocessing_modes() and its branch in prepare_solid.cpp.
#pragma once

#include "acd/mesh/labelled.h"
#include "acd/mesh/mesh.h"
#include "acd/solid/solid.h"

#include <string>
#include <vector>

namespace acd {

// Values are stable (scripts store labels, .mlx files the menu index of the table's rows).
enum class Preprocessing
{
	None,        // the mesh must be a valid solid
	AlphaWrap,   // always wrapped (CGAL's 3D alpha wrapping)
	Auto         // as given if a valid solid, else welded if that makes one, else wrapped
};

// The modes' labels and help, in menu order.
using PreprocessingMode = Labelled<Preprocessing>;
const std::vector<PreprocessingMode>& preprocessing_modes();

struct PrepareOptions
{
	Preprocessing mode      = Preprocessing::Auto;
	double        alpha     = 0.02;    // wrap alpha, a share of the input's enclosing diameter
	double        offset    = 0.001;   // wrap offset, the same
	double        max_alpha = 0.16;    // auto doubles alpha up to this while the wrap is a hollow skin
	bool          refuse_self_intersection = false;   // throw Error(SelfIntersection) for a crossing solid
};

struct PreparedSolid
{
	enum Done { AsGiven, Welded, Wrapped, Filled };   // values are reported (preprocessing_done)
	Solid       solid;
	Done        done    = AsGiven;
	int         welded  = 0;      // vertices merged into another
	int         filled  = 0;      // holes filled (Filled): faired, or on the planes their rims run on
	int         on_planes = 0;    // of them, those on planes
	double      alpha   = 0;      // the wrap's alpha kept, model units (0: not wrapped)
	double      alpha_share = 0;  // the same, a share of size
	double      offset  = 0;      // the wrap's offset, model units
	double      inside  = 1;      // share of the input's interior samples inside the wrap kept
	int         tries   = 0;      // wraps computed
	bool        capped  = false;  // openings closed along the input's winding-number level set
	bool        skin    = false;  // the input encloses no solid: the wrap is a thin skin about it
	double      cap_share  = 0;   // share of that level set spanning openings
	double      to_input   = 0;   // largest distance from the solid's surface to the input (model units)
	double      from_input = 0;   // and from the input's vertices to the solid (0 when as given)
	double      size    = 0;      // enclosing diameter of the input's finite vertices
	size_t      faces_in = 0;
	double      seconds  = 0;     // the preprocessing's wall time
	std::string reason;           // why the input was not used as given
	int         reason_code  = 0; // that error's Error::Code and count
	long        reason_count = 0;
};

// Throws Error(InvalidInput) when the mode cannot make a solid of the mesh (None and an invalid mesh, or
// nothing finite to wrap), and with refuse_self_intersection for a solid that crosses itself.
PreparedSolid prepare_solid(const TriMesh& mesh, const PrepareOptions& options);

// What was done, in a few words: "as given", "welded 12 vertices", "3 holes filled", "alpha_wrap 2%".
std::string describe(const PreparedSolid& p);

} // namespace acd
