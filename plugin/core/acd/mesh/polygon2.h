// Polygons with holes in the plane and the basics both the 2D decomposition and the 3D cut caps use:
// area, point in polygon, constrained Delaunay triangulation. A leaf: nothing here depends on either
// decomposition.
#pragma once

#include "acd/mesh/mesh.h"
#include "acd/mesh/measures.h"

#include <Eigen/Core>
#include <vector>

namespace acd {

using Vec2 = Eigen::Vector2d;
using Loop2 = std::vector<Vec2>;

// A polygon with holes: the outer loop counter-clockwise, each hole clockwise (interior on the left).
struct Polygon2
{
	Loop2              outer;
	std::vector<Loop2> holes;
};

double signed_area(const Loop2& loop);   // > 0 for counter-clockwise
double area(const Polygon2& p);           // outer minus holes
bool   inside(const Loop2& loop, const Vec2& p);   // even-odd rule

// Triangles of a polygon with holes (constrained Delaunay): vertices are the loops' points in order
// (outer, then holes), triangles counter-clockwise; inside is decided by nesting, so the loops'
// orientation does not matter. False if loops cross or two points coincide (numerically).
bool triangulate(const Polygon2& p, std::vector<Vec2>& V, std::vector<Tri>& F);

} // namespace acd
