// A convex hull cut down to what a physics engine accepts (vertices, polygons, triangles) while it still
// contains the exact hull: the budget is met by choosing which of the hull's facet planes to keep, never
// by dropping vertices, which would shrink the hull and open gaps that objects fall through.
#pragma once

#include "acd/hull/hull.h"

#include <string>
#include <vector>

namespace acd {

// Limits per hull; 0 is no limit.
struct HullBudget
{
	int vertices         = 0;
	int polygons         = 0;
	int triangles        = 0;
	int polygon_vertices = 0;   // corners of one polygon (PhysX's GPU path: 32)
	bool limited() const { return vertices > 0 || polygons > 0 || triangles > 0 || polygon_vertices > 0; }
	// The tighter of two budgets, limit by limit.
	HullBudget tighter(const HullBudget& o) const;
};

// The engines whose limits the hulls can be made to meet, in menu order.
enum class Engine { None, MuJoCo, PyBullet, PhysX, PhysXGpu, Unity };
struct EngineRow
{
	const char* label;
	Engine      id;
	const char* help;
	HullBudget  budget;
	double      thin_ratio;   // extent / inscribed radius above which the engine refuses a hull (0: never)
};
const std::vector<EngineRow>& engines();
const EngineRow&              engine(Engine e);

struct BoundedHull
{
	TriMesh mesh;                        // canonical order (the same bytes in every session)
	int     vertices = 0, polygons = 0, triangles = 0, polygon_vertices = 0;
	double  reach            = 0;        // farthest point of `mesh` from the exact hull (0: the exact hull)
	bool    reduced          = false;    // planes were dropped to meet the budget
	bool    within_budget    = true;
	double  inscribed_radius = 0;        // of the largest ball inside (measured when asked)
	double  extent           = 0;        // largest distance between two vertices (measured when asked)
};

// `exact` itself when no budget is set; with a budget, `exact` with its near-duplicate corners welded (held
// around every point) when that meets the budget; otherwise the intersection of as many of its facet planes (and
// at first four support planes) as the budget allows, each added where the intersection reaches farthest
// beyond the exact hull. Deterministic: the same hull in every run and on any thread count.
BoundedHull bounded_hull(const ConvexHull& exact, const HullBudget& budget, bool measure_inscribed = false);

// Radius of the largest ball inside the hull (a linear program over its facet planes).
double inscribed_radius(const ConvexHull& hull);

} // namespace acd
