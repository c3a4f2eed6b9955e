/****************************************************************************
* meshlab-acd: approximate convex decomposition for MeshLab                  *
* GPL-3.0-or-later, like MeshLab.                                            *
****************************************************************************/
#include "parameters.h"

#include <common/mlexception.h>

#include <acd/api/options.h>

#include <array>
#include <cmath>
#include <utility>

namespace acdml {

namespace {

// A choice's labels (what scripts and the GUI show) with the value each stands for, in menu order.
template <class E, size_t N> using Choices = std::array<std::pair<const char*, E>, N>;

template <class E, size_t N> QStringList labels(const Choices<E, N>& c)
{
	QStringList l;
	for (const auto& [label, value] : c) l << label;
	return l;
}

template <class E, size_t N> E chosen(const RichParameterList& par, const char* name, const Choices<E, N>& c)
{
	const int i = par.getEnum(name);
	return c[i >= 0 && i < (int) N ? i : 0].second;
}

// The core's table of options declares the 3D parameters; 2D keeps its own choices here.
const acd::Option& opt(const char* name) { return acd::option(name); }

QStringList labels(const acd::Option& o)
{
	QStringList l;
	for (const acd::OptionChoice& c : o.choices) l << c.label;
	return l;
}

template <class E> E chosen(const RichParameterList& par, const acd::Option& o)
{
	const int i = par.getEnum(o.name);
	return E(o.choices[i >= 0 && i < (int) o.choices.size() ? i : 0].value);
}

// A parameter declared from its row, with `value` as its default.
void add(RichParameterList& p, const acd::Option& o, double value)
{
	const QString help = QString::fromStdString(o.full_help());
	switch (o.kind) {
	case acd::Option::Number: p.addParam(RichFloat(o.name, (float) value, o.title, help)); break;
	case acd::Option::Integer: p.addParam(RichInt(o.name, (int) value, o.title, help)); break;
	case acd::Option::Flag: p.addParam(RichBool(o.name, value != 0, o.title, help)); break;
	case acd::Option::Choice: p.addParam(RichEnum(o.name, o.index_of((int) value), labels(o), o.title, help)); break;
	}
}
void add(RichParameterList& p, const char* name) { add(p, opt(name), opt(name).value); }

const Choices<acd::CutLineSelection, 2> kCutLines = {{{"best", acd::CutLineSelection::Best},
                                                      {"bisector", acd::CutLineSelection::Bisector}}};
// A polygon's holes take the same labels as a solid's cavities (scripts use either filter alike).
const Choices<acd::HoleCut, 3> kHoleCuts = {{{"best_plane", acd::HoleCut::BestLine},
                                             {"principal_plane", acd::HoleCut::PrincipalAxis},
                                             {"keep_cavities", acd::HoleCut::KeepHoles}}};

// tau and its unit as 2D declares them (3D's come from the table).
void add_tau(RichParameterList& p, float tau, const QString& size_of)
{
	p.addParam(RichFloat("tau", tau, "Concavity tolerance (tau)",
	                     "Largest concavity a piece may keep. With tau_unit = percent_of_size it is a percentage of the "
	                     "diameter of the " + size_of + "; with model_units it is an absolute length."));
	add(p, "tau_unit");
}

} // namespace

void add_decomposition_parameters(RichParameterList& p, const DecompositionParameters& which)
{
	for (const acd::Option& o : acd::decomposition_options()) {
		const std::string name = o.name;
		if ((name == "output_hulls" && !which.output_hulls) || ((name == "max_hull_vertices" || name == "engine") && !which.max_hull_vertices)) continue;
		if ((name == "merge_parts" || name == "merge_measure" || name == "cut_search") && !which.merge) continue;   // the skeleton's one tree
		double value = o.value;
		if (name == "tau" && which.tau > 0) value = which.tau;
		if (name == "cut_plane_selection" && which.cut_plane) value = o.value_of(which.cut_plane);
		add(p, o, value);
	}
}

void add_polygon_parameters(RichParameterList& p)
{
	add_tau(p, 1.0, "polygon's smallest enclosing circle");
	p.addParam(RichEnum(
		"cut_line_selection", 0, labels(kCutLines), "Cutting line",
		"best: try several cuts from the notch (the bisector, directions spread between its two edges' "
		"extensions, towards nearby notches) and keep the bisector unless another leaves clearly less "
		"concave pieces; bisector: the paper's cut along the bisector of the notch's edge normals."));
	p.addParam(RichEnum(
		"hole_handling", 0, labels(kHoleCuts), "Holes",
		"As in 3D, for a polygon's holes: principal_plane: the paper's cut along the hole's principal axis "
		"through its centre; best_plane: that axis, the minor axis and 6 more directions through the "
		"centre, keeping the cut leaving the least concave pieces; keep_cavities: never cut for a hole, "
		"measure the outer boundary only and report the holes kept (those pieces are not tau-convex)."));
	p.addParam(RichEnum("hole_order", 0, labels(opt("hole_order")), "Hole order",
	                    "first: the paper (a hole's concavity is infinite): holes are cut before any notch; "
	                    "by_concavity: a hole is cut when its depth below the hull is the largest concavity."));
	p.addParam(RichInt("max_parts", 0, "Maximum number of pieces",
	                   "Stop after this many pieces (0 = no limit); the most concave notches are cut first."));
	p.addParam(RichString("tree_file", "", "Save tree as (JSON)",
	                      "If set, the cut tree of each polygon (nodes, paths, cuts, concavity, area) is "
	                      "written to this JSON file. Empty: not written.", true));
}

void add_level_of_detail_parameters(RichParameterList& p)
{
	p.addParam(RichString("tree_file", "", "Saved tree (JSON)",
	                      "The tree_file written by 'Approximate Convex Decomposition' (with part geometry)."));
	p.addParam(RichEnum("level_by", 0, QStringList{"tau", "depth"}, "Level by",
	                    "tau: cut the tree where parts are within this tau; depth: at this tree depth."));
	p.addParam(RichFloat("tau", 5.0, "Coarser tau",
	                     "With level_by = tau: the concavity a part may keep (at least the tree's own tau)."));
	add(p, "tau_unit");
	p.addParam(RichInt("depth", 1, "Depth", "With level_by = depth: the root is depth 0."));
	p.addParam(RichBool("output_hulls", false, "Also add part hulls",
	                    "Add each part's saved convex hull as a layer (acd_hull_<path>)."));
}

double tau_in_model_units(const RichParameterList& par, double size)
{
	const double tau = par.getFloat("tau");
	if (!(tau > 0) || !std::isfinite(tau)) throw MLException(QString("tau must be positive (got %1).").arg(tau));
	return chosen<acd::TauUnit>(par, opt("tau_unit")) == acd::TauUnit::PercentOfSize ? tau / 100.0 * size : tau;
}

acd::DecomposeOptions decompose_options(const RichParameterList& par, double size, vcg::CallBackPos* cb)
{
	acd::DecomposeOptions o;
	o.tau                 = tau_in_model_units(par, size);
	o.cut_plane_selection = chosen<acd::CutPlaneSelection>(par, opt("cut_plane_selection"));
	o.max_parts           = par.getInt("max_parts");
	o.hole_handling       = chosen<acd::HoleHandling>(par, opt("hole_handling"));
	o.hole_order          = chosen<acd::HoleOrder>(par, opt("hole_order"));
	o.time_limit_seconds  = par.getFloat("time_limit");
	o.threads             = par.getInt("threads");
	// The skeleton follows the cut tree, so its filter has no merge.
	o.merge_parts         = par.hasParameter("merge_parts") && par.getBool("merge_parts");
	if (par.hasParameter("merge_measure")) o.merge_measure = chosen<acd::MergeMeasure>(par, opt("merge_measure"));
	o.cut_search          = par.hasParameter("cut_search") ? chosen<acd::CutSearch>(par, opt("cut_search")) : acd::CutSearch::Fast;
	if (o.max_parts < 0) throw MLException("max_parts must be 0 (no limit) or positive.");
	if (o.time_limit_seconds < 0) throw MLException("time_limit must be 0 (no limit) or positive.");
	if (o.threads < 0) throw MLException("threads must be 0 (every core) or positive.");
	if (cb) o.progress = [cb](int pct, const char* msg) { return cb(pct, msg); };
	return o;
}

acd::PolygonOptions polygon_options(const RichParameterList& par, double size)
{
	acd::PolygonOptions o;
	o.tau                = tau_in_model_units(par, size);
	o.cut_line_selection = chosen(par, "cut_line_selection", kCutLines);
	o.hole_handling      = chosen(par, "hole_handling", kHoleCuts);
	o.hole_order         = chosen<acd::HoleOrder>(par, opt("hole_order"));
	o.max_parts          = par.getInt("max_parts");
	if (o.max_parts < 0) throw MLException("max_parts must be 0 (no limit) or positive.");
	return o;
}

acd::Engine hull_engine(const RichParameterList& par) { return chosen<acd::Engine>(par, opt("engine")); }

acd::PrepareOptions prepare_options(const RichParameterList& par)
{
	acd::PrepareOptions o;
	o.mode   = chosen<acd::Preprocessing>(par, opt("preprocessing"));
	o.alpha  = par.getFloat("wrap_alpha") / 100;
	o.offset = par.getFloat("wrap_offset") / 100;
	o.refuse_self_intersection = chosen<int>(par, opt("on_self_intersection")) == 1;
	if (o.mode != acd::Preprocessing::None && (!(o.alpha > 0) || !(o.offset > 0))) throw MLException("wrap_alpha and wrap_offset must be positive.");
	return o;
}

} // namespace acdml
