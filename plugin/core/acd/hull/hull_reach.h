// How far a part's convex hull reaches beyond the part: the largest distance from a point of a bridge
// (a hull facet the surface does not fully cover) to the part's surface. It is what a collision hull
// adds to the part it stands for, so a part is tau-convex only if this is at most tau too; notch
// distances alone miss it where a pocket has few vertices (a bore, a slot, a keyway in a low-poly
// CAD part: every vertex on the hull, the hull far from the surface in between).
#pragma once

#include "acd/hull/hull.h"

namespace acd {

struct HullReach
{
	double lower = 0;           // attained: `witness` lies this far from the surface
	double upper = 0;           // no point of the bridges lies farther
	Vec3   witness = Vec3::Zero();   // the farthest bridge point found
	Vec3   nearest = Vec3::Zero();   // its nearest point of the surface
	int    facet = -1;          // the bridge holding the witness (-1: no bridge lies off the surface)
	int    evaluations = 0;     // distance queries made
};

// Branch and bound over the bridges' triangles. The distance to a surface is 1-Lipschitz, so a
// triangle whose centre lies at d from the surface, with its corners within R of the centre, holds
// no point farther than d + R; and it is at most the distance to any one face, which is convex, so
// no farther than that face is from the triangle's corners. The triangle with the largest bound is split in four until every
// bound is settled: at most floor + slack while nothing beyond floor + slack is found (the reach is
// then certified below floor + slack, in any pose: a point found between floor and floor + slack does
// not end the search), else within `relative` (and slack) of the farthest point found.
// `max_evaluations` bounds the work: past it, `upper` keeps the largest bound left.
HullReach hull_reach(const TriMesh& m, const ConvexHull& hull, const std::vector<char>& bridge, double floor,
                     double slack, double relative = 0.02, int max_evaluations = 200000);

} // namespace acd
