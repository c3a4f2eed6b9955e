#include "acd/structure/collision_hulls.h"
#include "acd/mesh/parallel.h"

#include <algorithm>

namespace acd {

CollisionHulls collision_hulls(const Decomposition& d, Engine engine, int max_vertices)
{
	CollisionHulls out;
	const EngineRow& row = acd::engine(engine);
	out.engine           = engine;
	out.budget           = row.budget.tighter(HullBudget{std::max(0, max_vertices), 0, 0, 0});
	out.nodes            = d.parts();
	out.hulls.resize(out.nodes.size());
	out.thin.assign(out.nodes.size(), 0);
	const bool measure = engine != Engine::None || out.budget.limited();
	parallel_for(out.nodes.size(), [&](size_t i) {
		out.hulls[i] = bounded_hull(ConvexHull(d.nodes[out.nodes[i]].mesh.V), out.budget, measure);
		const BoundedHull& h = out.hulls[i];
		out.thin[i] = row.thin_ratio > 0 && h.extent > row.thin_ratio * h.inscribed_radius;
	});
	for (size_t i = 0; i < out.hulls.size(); ++i) {
		out.max_reach = std::max(out.max_reach, out.hulls[i].reach);
		out.reduced += out.hulls[i].reduced;
		out.over_budget += !out.hulls[i].within_budget;
		out.thin_count += out.thin[i];
	}
	return out;
}

} // namespace acd
