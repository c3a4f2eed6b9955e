// What the 2D stages share (internal to polygon/): the exact-predicates kernel, the cross product and
// a pose-invariant size.
#pragma once

#include "acd/mesh/polygon2.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <string>

namespace acd {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

[[noreturn]] inline void invalid(const std::string& m) { throw Error(Error::InvalidInput, m); }

inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Twice the largest distance from the points' centroid: a size that does not change with pose.
inline double extent2(const Loop2& pts)
{
	Vec2 c = Vec2::Zero();
	for (const Vec2& p : pts) c += p;
	c /= (double) pts.size();
	double r = 0;
	for (const Vec2& p : pts) r = std::max(r, (p - c).norm());
	return 2 * r;
}

} // namespace acd
