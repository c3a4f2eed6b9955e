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

#include <acd/decompose.h>
#include <acd/polygon.h>

namespace acdml {

// Parameters of the filters that decompose a mesh (decomposition, skeleton, hull union); `tau`
// and the cut's default differ per filter; `merge` offers merge_parts (off where absent).
void add_decomposition_parameters(RichParameterList& p, float tau, int cut_plane_default, bool output_hulls,
                                  bool max_hull_vertices, bool merge);
void add_polygon_parameters(RichParameterList& p);
void add_level_of_detail_parameters(RichParameterList& p);

// tau in model units: a percentage of `size` or a length, as tau_unit says; refused unless positive.
double tau_in_model_units(const RichParameterList& par, double size);

// The core's options from the parameters (sizes in model units; progress through `cb`).
acd::DecomposeOptions decompose_options(const RichParameterList& par, double size, vcg::CallBackPos* cb);
acd::PolygonOptions   polygon_options(const RichParameterList& par, double size);

enum class Preprocessing { None, AlphaWrap, Auto };
Preprocessing preprocessing(const RichParameterList& par);
bool          refuse_self_intersection(const RichParameterList& par);

} // namespace acdml

#endif
