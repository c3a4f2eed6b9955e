#include "acd/api/options.h"

namespace acd {

namespace {

template <class Row> std::vector<OptionChoice> rows(const std::vector<Row>& table)
{
	std::vector<OptionChoice> out;
	for (const Row& r : table) out.push_back({r.label, (int) r.id, r.help});
	return out;
}

std::vector<OptionChoice> cavity_choices()
{
	return {{"best_plane", (int) HoleHandling::BestPlane,
	         "the principal plane, the other two principal planes and planes through the cavity towards the "
	         "nearest hull facet, keeping the one leaving the least concave parts"},
	        {"principal_plane", (int) HoleHandling::PrincipalPlane,
	         "the paper's cut through the cavity's centre along its principal plane (the plane of its two major axes)"},
	        {"keep_cavities", (int) HoleHandling::KeepCavities,
	         "never cut for a cavity, measure concavity on the outer surface only and report the cavities left "
	         "inside parts (those parts are then not tau-convex)"}};
}

std::vector<OptionChoice> merge_measures()
{
	return {{"hull_distance", (int) MergeMeasure::HullDistance,
	         "its hull's distance to it: how far the collision hull reaches beyond the union, certified as every "
	         "part's is (a pocket the hull spans, such as a slot narrower than tau, may then stay in one part: its "
	         "floor lies deeper than tau below the hull); a part whose hull is so within tau is not cut either"},
	        {"concavity", (int) MergeMeasure::Concavity,
	         "that and the cuts' own measure, every notch within tau of its bridge (the paper's concavity): merged "
	         "parts are tau-convex as the cut tree's leaves are, and more of them"}};
}

std::vector<OptionChoice> cut_searches()
{
	return {{"thorough", (int) CutSearch::Thorough,
	         "grow the cut tree twice, each cut picked by another rule (its worse part's concavity, as the paper; or "
	         "the parts both its parts are estimated to need afterwards, with the planes across the part's principal axes "
	         "among the candidates), merge both and keep the one with fewer parts "
	         "(about twice the time; a mesh of over 30,000 faces grows both on its simplified copy and certifies the "
	         "better)"},
	        {"fast", (int) CutSearch::Fast, "one cut tree, each cut picked by its worse part's concavity (the paper's "
	                                        "greedy search)"}};
}

std::vector<Option> make_table()
{
	using O = Option;
	return {
		{"tau", O::Number, 2.5, "Concavity tolerance (tau)",
		 "Largest concavity a part may keep, and how far any part's hull may reach beyond the part. With tau_unit = "
		 "percent_of_size it is a percentage of the diameter of the mesh's smallest enclosing sphere (a size that "
		 "does not change when the shape is rotated); with model_units it is an absolute length.", {}},
		{"tau_unit", O::Choice, (int) TauUnit::PercentOfSize, "Unit of tau", "The unit of tau.",
		 {{"percent_of_size", (int) TauUnit::PercentOfSize, "a percentage of the mesh's enclosing-sphere diameter"},
		  {"model_units", (int) TauUnit::ModelUnits, "a length in the layer's units"}}},
		{"cut_plane_selection", O::Choice, (int) CutPlaneSelection::BisectorOrFace, "Cutting plane",
		 "How the plane through the most concave notch is chosen.", rows(cut_strategies())},
		{"hole_handling", O::Choice, (int) HoleHandling::BestPlane, "Cavities (hole boundaries)",
		 "How closed inner shells (cavities) are resolved; their notches never reach the hull.",
		 cavity_choices()},
		{"hole_order", O::Choice, (int) HoleOrder::First, "Cavity order", "When a cavity is cut.",
		 {{"first", (int) HoleOrder::First, "the paper (a cavity's concavity is infinite): every cavity is cut before any notch"},
		  {"by_concavity", (int) HoleOrder::ByConcavity, "a cavity is cut when its depth below the hull is the largest concavity left"}}},
		{"max_parts", O::Integer, 0, "Maximum number of parts",
		 "Stop after this many parts (0 = no limit); the most concave notches are cut first, and the result reports "
		 "whether the limit was reached.", {}},
		{"merge_parts", O::Flag, 1, "Merge neighbouring parts",
		 "After the cuts, merge parts that share a cut face while their union stays within tau (by merge_measure), "
		 "the least concave union first: fewer parts, still an exact partition. By hull_distance, parts of "
		 "separate solids of the input (an assembly's pieces) merge too where one hull stays within tau of both. "
		 "Off: the cut tree's leaves as they are.", {}},
		{"merge_measure", O::Choice, (int) MergeMeasure::HullDistance, "Merge while within tau by",
		 "What a union of neighbouring parts must stay within tau by to be merged.", merge_measures()},
		{"cut_search", O::Choice, (int) CutSearch::Thorough, "Cut search", "How hard the search for cuts looks.",
		 cut_searches()},
		{"output_hulls", O::Flag, 0, "Also add part hulls",
		 "Add the convex hull of each part as a layer too (named acd_hull_<path>).", {}},
		{"max_hull_vertices", O::Integer, 0, "Maximum hull vertices",
		 "With output_hulls: at most this many vertices per hull (0 = no limit), on top of the engine's limits. "
		 "A hull over it keeps as many of its facet planes as fit, so it still contains its part and reaches a "
		 "little beyond the exact hull (reported).", {}},
		{"engine", O::Choice, (int) Engine::None, "Physics engine",
		 "Make every hull meet this engine's limits (and add the hull layers). A hull over them keeps as many of its "
		 "facet planes as fit: it still contains its part, and the result reports how far it reaches beyond the exact "
		 "hull.", rows(engines())},
		{"preprocessing", O::Choice, (int) Preprocessing::Auto, "Preprocessing",
		 "How the mesh becomes the solid that is cut.", rows(preprocessing_modes())},
		{"wrap_alpha", O::Number, 2.0, "Alpha wrap: alpha (%)",
		 "With alpha_wrap: gaps, holes and cavities narrower than about this are closed, as a percentage of the "
		 "enclosing-sphere diameter (smaller keeps more detail and costs more).", {}},
		{"wrap_offset", O::Number, 0.1, "Alpha wrap: offset (%)",
		 "With alpha_wrap: how far outside the input the wrap lies, i.e. how far it may move the surface, as a "
		 "percentage of the enclosing-sphere diameter.", {}},
		{"on_self_intersection", O::Choice, 0, "If the mesh intersects itself", "What a crossing solid gets.",
		 {{"warn", 0, "decompose anyway and say so in the log and result (slight crossings, common in scans, are "
		              "harmless; a cut that would make an open part fails with a message instead)"},
		  {"refuse", 1, "stop with an error"}}},
		{"threads", O::Integer, 0, "Threads",
		 "Threads the decomposition may use (0 = every core). The parts are the same for any count; a batch of "
		 "several meshes at once gives each its share.", {}},
		{"time_limit", O::Number, 0, "Time limit (s)",
		 "Stop cutting after this many seconds (0 = no limit) and return the parts found so far; merging "
		 "(merge_parts) shares the same limit and stops with the parts it has merged.", {}},
	};
}

} // namespace

int Option::index_of(int v) const
{
	for (size_t i = 0; i < choices.size(); ++i)
		if (choices[i].value == v) return (int) i;
	return -1;
}

int Option::value_of(const std::string& label) const
{
	for (const OptionChoice& c : choices)
		if (label == c.label) return c.value;
	return -1;
}

std::string Option::labels() const
{
	std::string s;
	for (const OptionChoice& c : choices) s += (s.empty() ? "" : " | ") + std::string(c.label);
	return s;
}

std::string Option::full_help() const
{
	std::string s = help;
	for (const OptionChoice& c : choices) s += std::string(" ") + c.label + ": " + c.help + ";";
	if (!choices.empty()) s.back() = '.';
	return s;
}

const std::vector<Option>& decomposition_options()
{
	static const std::vector<Option> table = make_table();
	return table;
}

const Option& option(const std::string& name)
{
	for (const Option& o : decomposition_options())
		if (name == o.name) return o;
	throw Error(Error::InvalidOption, "No option named " + name + ".");
}

} // namespace acd
