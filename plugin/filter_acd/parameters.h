/****************************************************************************
* meshlab-acd: approximate convex decomposition for MeshLab                  *
* GPL-3.0-or-later, like MeshLab.                                            *
****************************************************************************/
// The filters' parameters: declared from one table per choice (label and core value side by side),
// and read back into the core's options with the same tables.
#ifndef FILTER_ACD_PARAMETERS_H
#define FILTER_ACD_PARAMETERS_H

#include <common/parameters/rich_parameter_list.h>
#include <common/parameters/rich_parameters.h>
#include <wrap/callback.h>   // vcg::CallBackPos

#include <acd/decompose3/decompose.h>
#include <acd/hull/bounded_hull.h>
#include <acd/polygon/polygon.h>
#include <acd/prepare/prepare_solid.h>

namespace acdml {

// Which of the decomposition's parameters a filter declares, and where its defaults differ from the
// options table's (acd/api/options.h).
struct DecompositionParameters
{
	double      tau = -1;               // < 0: the table's
	const char* cut_plane = nullptr;    // a label; nullptr: the table's
	bool        output_hulls = false;
	bool        max_hull_vertices = false;
	bool        merge = false;          // merge_parts (the skeleton follows the cut tree: none)
};
void add_decomposition_parameters(RichParameterList& p, const DecompositionParameters& which);
void add_polygon_parameters(RichParameterList& p);
void add_level_of_detail_parameters(RichParameterList& p);

// tau in model units: a percentage of `size` or a length, as tau_unit says; refused unless positive.
double tau_in_model_units(const RichParameterList& par, double size);

// The core's options from the parameters (sizes in model units; progress through `cb`).
acd::DecomposeOptions decompose_options(const RichParameterList& par, double size, vcg::CallBackPos* cb);
acd::PolygonOptions   polygon_options(const RichParameterList& par, double size);

// The engine whose limits the hulls meet (engine).
acd::Engine hull_engine(const RichParameterList& par);

// How the mesh is prepared (preprocessing, wrap_alpha, wrap_offset, on_self_intersection).
acd::PrepareOptions prepare_options(const RichParameterList& par);

} // namespace acdml

#endif
