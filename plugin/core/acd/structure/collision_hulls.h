// The parts' hulls as a physics engine takes them: each within the engine's budget (bounded_hull) and
// still containing its part, with what each reduction cost.
#pragma once

#include "acd/decompose3/decompose.h"
#include "acd/hull/bounded_hull.h"

#include <vector>

namespace acd {

struct CollisionHulls
{
	Engine                   engine = Engine::None;
	HullBudget               budget;
	std::vector<int>         nodes;   // the part each hull stands for (Decomposition::parts() order)
	std::vector<BoundedHull> hulls;
	std::vector<char>        thin;    // the engine would refuse it (in-sphere far below its extent)
	double                   max_reach = 0;   // farthest any hull reaches beyond its exact hull
	int                      reduced = 0, over_budget = 0, thin_count = 0;
};

// Every part's hull, cut to the budget of `engine` tightened by `max_vertices` (0: none). Parts are
// done in parallel; the result does not depend on the thread count.
CollisionHulls collision_hulls(const Decomposition& d, Engine engine, int max_vertices);

} // namespace acd
