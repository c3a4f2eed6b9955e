/****************************************************************************
* meshlab-acd: approximate convex decomposition for MeshLab                  *
* GPL-3.0-or-later, like MeshLab.                                            *
****************************************************************************/
#include "parameters.h"

#include <common/mlexception.h>

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

enum class TauUnit { PercentOfSize, ModelUnits };

const Choices<TauUnit, 2> kTauUnits = {{{"percent_of_size", TauUnit::PercentOfSize}, {"model_units", TauUnit::ModelUnits}}};
// New choices go last: .mlx scripts store the index.
const Choices<acd::CutPlaneSelection, 4> kCutPlanes = {{{"best", acd::CutPlaneSelection::Best},
                                                        {"bisector", acd::CutPlaneSelection::Bisector},
                                                        {"min_section", acd::CutPlaneSelection::MinSection},
                                                        {"bisector_or_face", acd::CutPlaneSelection::BisectorOrFace}}};
const Choices<acd::CutLineSelection, 2> kCutLines = {{{"best", acd::CutLineSelection::Best},
                                                      {"bisector", acd::CutLineSelection::Bisector}}};
const Choices<acd::HoleHandling, 3> kCavityCuts = {{{"best_plane", acd::HoleHandling::BestPlane},
                                                    {"principal_plane", acd::HoleHandling::PrincipalPlane},
                                                    {"keep_cavities", acd::HoleHandling::KeepCavities}}};
// A polygon's holes take the same labels as a solid's cavities (scripts use either filter alike).
const Choices<acd::HoleCut, 3> kHoleCuts = {{{"best_plane", acd::HoleCut::BestLine},
                                             {"principal_plane", acd::HoleCut::PrincipalAxis},
                                             {"keep_cavities", acd::HoleCut::KeepHoles}}};
const Choices<acd::HoleOrder, 2> kHoleOrders = {{{"first", acd::HoleOrder::First},
                                                 {"by_concavity", acd::HoleOrder::ByConcavity}}};
const Choices<Preprocessing, 3> kPreprocessing = {{{"none", Preprocessing::None},
                                                   {"alpha_wrap", Preprocessing::AlphaWrap},
                                                   {"auto", Preprocessing::Auto}}};
const Choices<bool, 2> kOnSelfIntersection = {{{"warn", false}, {"refuse", true}}};

// The alpha wrap's two lengths (percentages of the size), in menu order.
struct Number
{
	const char* name;
	float       value;
	const char* label;
	const char* help;
};
const Number kWrapNumbers[] = {
	{"wrap_alpha", 2.0f, "Alpha wrap: alpha (%)",
	 "With alpha_wrap: gaps, holes and cavities narrower than about this are closed, as a percentage of the "
	 "enclosing-sphere diameter (smaller keeps more detail and costs more)."},
	{"wrap_offset", 0.1f, "Alpha wrap: offset (%)",
	 "With alpha_wrap: how far outside the input the wrap lies, i.e. how far it may move the surface, as a "
	 "percentage of the enclosing-sphere diameter."},
};

// tau and its unit, as 3D and 2D declare them (`size_of`: what the percentage is of).
void add_tau(RichParameterList& p, float tau, const QString& size_of)
{
	p.addParam(RichFloat("tau", tau, "Concavity tolerance (tau)",
	                     "Largest concavity a part may keep. With tau_unit = percent_of_size it is a percentage of the "
	                     "diameter of the " + size_of + " (a size that does not change when the shape is rotated); "
	                     "with model_units it is an absolute length."));
	p.addParam(RichEnum("tau_unit", 0, labels(kTauUnits), "Unit of tau",
	                    "percent_of_size: tau is a percentage of the " + size_of + "'s diameter; model_units: tau "
	                    "is a length in the layer's units."));
}

} // namespace

void add_decomposition_parameters(RichParameterList& p, float tau, int cut_plane_default, bool output_hulls,
                                  bool max_hull_vertices, bool merge)
{
	add_tau(p, tau, "mesh's smallest enclosing sphere");
	p.addParam(RichEnum(
		"cut_plane_selection", cut_plane_default, labels(kCutPlanes), "Cutting plane",
		"best: try several planes through the notch (the bisector, planes around its retraction "
		"direction, the plane parallel to its bridge) and keep the one leaving the least concave parts; "
		"bisector: the paper's plane through the notch edge bisecting its reflex angle (faster); "
		"min_section: of the planes through the notch and its retraction direction, the one cutting the "
		"smallest cross-section (the neck), which surface noise hardly moves (the skeleton's default); "
		"bisector_or_face: the bisector, or at a sharp notch edge (a CAD step, slot or flange) one of its two "
		"faces extended, or the plane of the rim the notch edge lies on (a groove's or step's ring), or the "
		"flat a shallow notch rises from (a low boss or ramp on a plate), when that leaves clearly less "
		"concave parts (near the bisector's speed)."));
	p.addParam(RichEnum(
		"hole_handling", 0, labels(kCavityCuts), "Cavities (hole boundaries)",
		"How closed inner shells (cavities) are resolved; their notches never reach the hull. "
		"principal_plane: the paper's cut through the cavity's centre along its principal plane (the "
		"plane of its two major axes); best_plane: that plane, the other two principal planes and planes "
		"through the cavity towards the nearest hull facet, keeping the one leaving the least concave "
		"parts; keep_cavities: never cut for a cavity, measure concavity on the outer surface only and "
		"report the cavities left inside parts (those parts are then not tau-convex)."));
	p.addParam(RichEnum(
		"hole_order", 0, labels(kHoleOrders), "Cavity order",
		"first: the paper (a cavity's concavity is infinite): every cavity is cut before any notch; "
		"by_concavity: a cavity is cut when its depth below the hull is the largest concavity left."));
	p.addParam(RichInt(
		"max_parts", 0, "Maximum number of parts",
		"Stop after this many parts (0 = no limit); the most concave notches are cut first, and the "
		"result reports whether the limit was reached."));
	if (merge)
		p.addParam(RichBool(
			"merge_parts", true, "Merge neighbouring parts",
			"After the cuts, merge parts that share a cut face while their union stays within tau (by the "
			"same measure as the cuts, hull distance included), the least concave union first: fewer "
			"parts, still an exact partition. Off: the cut tree's leaves as they are."));
	if (output_hulls)
		p.addParam(RichBool("output_hulls", false, "Also add part hulls",
		                    "Add the convex hull of each part as a layer too (named acd_hull_<path>)."));
	if (max_hull_vertices)
		p.addParam(RichInt("max_hull_vertices", 0, "Maximum hull vertices",
		                   "With output_hulls: limit each hull to this many vertices (0 = no limit), as physics "
		                   "engines require; extra vertices are dropped (the hull shrinks slightly)."));
	p.addParam(RichEnum(
		"preprocessing", 0, labels(kPreprocessing), "Preprocessing",
		"none: the mesh must be a closed, 2-manifold, oriented solid that does not intersect itself; "
		"alpha_wrap: first wrap it with CGAL's 3D alpha wrapping, which turns open, non-manifold, "
		"self-intersecting meshes, triangle soups and point clouds into one closed solid (the parts "
		"then decompose the wrap, which lies about wrap_offset outside the input); auto: as given when "
		"it is a valid solid, else welded (vertices within 1e-5 of its size) if that makes it one, else "
		"alpha wrapped, doubling alpha (up to 16%) while the wrap is a hollow skin that slipped inside "
		"through small holes; an open shell that no such wrap fills keeps the first wrap, its skin."));
	for (const Number& n : kWrapNumbers) p.addParam(RichFloat(n.name, n.value, n.label, n.help));
	p.addParam(RichEnum(
		"on_self_intersection", 0, labels(kOnSelfIntersection), "If the mesh intersects itself",
		"warn: decompose anyway and say so in the log and result (slight crossings, common in scans, "
		"are harmless; a cut that would make an open part fails with a message instead); refuse: stop "
		"with an error."));
	p.addParam(RichFloat("time_limit", 0, "Time limit (s)",
	                     "Stop cutting after this many seconds (0 = no limit) and return the parts found so far; merging "
	                     "(merge_parts) shares the same limit and stops with the parts it has merged."));
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
	p.addParam(RichEnum("hole_order", 0, labels(kHoleOrders), "Hole order",
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
	p.addParam(RichEnum("tau_unit", 0, labels(kTauUnits), "Unit of tau",
	                    "percent_of_size: a percentage of the mesh's enclosing-sphere diameter; model_units."));
	p.addParam(RichInt("depth", 1, "Depth", "With level_by = depth: the root is depth 0."));
	p.addParam(RichBool("output_hulls", false, "Also add part hulls",
	                    "Add each part's saved convex hull as a layer (acd_hull_<path>)."));
}

double tau_in_model_units(const RichParameterList& par, double size)
{
	const double tau = par.getFloat("tau");
	if (!(tau > 0) || !std::isfinite(tau)) throw MLException(QString("tau must be positive (got %1).").arg(tau));
	return chosen(par, "tau_unit", kTauUnits) == TauUnit::PercentOfSize ? tau / 100.0 * size : tau;
}

acd::DecomposeOptions decompose_options(const RichParameterList& par, double size, vcg::CallBackPos* cb)
{
	acd::DecomposeOptions o;
	o.tau                 = tau_in_model_units(par, size);
	o.cut_plane_selection = chosen(par, "cut_plane_selection", kCutPlanes);
	o.max_parts           = par.getInt("max_parts");
	o.hole_handling       = chosen(par, "hole_handling", kCavityCuts);
	o.hole_order          = chosen(par, "hole_order", kHoleOrders);
	o.time_limit_seconds  = par.getFloat("time_limit");
	// The skeleton follows the cut tree, so its filter has no merge.
	o.merge_parts         = par.hasParameter("merge_parts") && par.getBool("merge_parts");
	if (o.max_parts < 0) throw MLException("max_parts must be 0 (no limit) or positive.");
	if (o.time_limit_seconds < 0) throw MLException("time_limit must be 0 (no limit) or positive.");
	if (cb) o.progress = [cb](int pct, const char* msg) { return cb(pct, msg); };
	return o;
}

acd::PolygonOptions polygon_options(const RichParameterList& par, double size)
{
	acd::PolygonOptions o;
	o.tau                = tau_in_model_units(par, size);
	o.cut_line_selection = chosen(par, "cut_line_selection", kCutLines);
	o.hole_handling      = chosen(par, "hole_handling", kHoleCuts);
	o.hole_order         = chosen(par, "hole_order", kHoleOrders);
	o.max_parts          = par.getInt("max_parts");
	if (o.max_parts < 0) throw MLException("max_parts must be 0 (no limit) or positive.");
	return o;
}

Preprocessing preprocessing(const RichParameterList& par) { return chosen(par, "preprocessing", kPreprocessing); }

bool refuse_self_intersection(const RichParameterList& par) { return chosen(par, "on_self_intersection", kOnSelfIntersection); }

} // namespace acdml
