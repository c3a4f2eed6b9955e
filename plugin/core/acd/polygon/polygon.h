// 2D approximate convex decomposition of polygons with holes (the paper's Section 5, Algorithms
// 5.1-5.3): notch concavity is the distance to the bridge line of the notch's pocket on the outer
// boundary's hull; the most concave notch is cut from the notch into the polygon (bisector of its
// edges' normals, or the best-scored of several directions), holes are cut along their principal
// axis; Separate2D cuts only the stretch of the line between the outer-boundary edges nearest to the
// notch on either side, splitting the holes it crosses, and always yields exactly two polygons.
#pragma once

#include "acd/recursion/hole_order.h"
#include "acd/mesh/polygon2.h"
#include "acd/recursion/hole_order.h"

#include <Eigen/Core>

namespace acd {

// Loops in any orientation and order -> polygons with holes. Nesting decides (point in polygon): a loop
// inside an even number of others bounds material from outside (made counter-clockwise), an odd
// number is a hole of the smallest loop around it (made clockwise). Throws Error(InvalidInput) for
// loops with fewer than 3 distinct points, non-finite coordinates, zero area, self-crossings, or loops
// that cross each other.
std::vector<Polygon2> polygons_from_loops(std::vector<Loop2> loops);

// A line n.x = d (unit n); for a notch cut the cut runs from `from` along `dir`.
struct Line2
{
	Vec2   n = Vec2(0, 1);
	double d = 0;
};

struct Concavity2
{
	std::vector<double> outer;   // per outer vertex: distance to its pocket's bridge line, 0 on the hull
	std::vector<double> hole_depth;   // per hole: deepest vertex's distance below the hull's boundary
	double max_concavity = 0;    // over outer notches (reflex vertices)
	int    max_vertex = -1;      // outer vertex index of the most concave notch
	int    notches = 0;          // reflex outer vertices
	int    bridges = 0;
};

// Algorithm 5.1 on the outer boundary; holes measured only by their depth below the hull.
Concavity2 measure_concavity(const Polygon2& p);

struct Node2
{
	int         parent = -1;
	int         child[2] = {-1, -1};
	std::string path;
	double      concavity = 0;   // outer notches only; holes are counted in `holes`
	double      area = 0;
	int         notch_count = 0;   // reflex outer vertices
	int         hole_count = 0;
	Vec2        notch = Vec2::Zero();
	bool        has_cut = false;
	Vec2        cut_from = Vec2::Zero(), cut_to = Vec2::Zero();   // the cut's extreme points
	Line2       line;
	bool        hole_cut = false;
	bool        uncut = false;
	Polygon2    polygon;
	bool        leaf() const { return child[0] < 0; }
};

struct Decomposition2
{
	std::vector<Node2> nodes;
	double             tau = 0;
	bool               max_parts_reached = false;
	bool               time_limit_reached = false;
	int                hole_cuts = 0;
	int                kept_holes = 0;
	std::vector<int>   leaves() const;   // in path order
	double             max_leaf_concavity() const;
};

enum class CutLineSelection
{
	Bisector,   // the paper: the bisector of the notch's edge normals
	Best        // several directions in the notch's cone (and towards notches in it), least concave pieces
};

enum class HoleCut
{
	PrincipalAxis,   // the paper: the line through the hole's centre along its major axis
	BestLine,        // the best-scored of several lines through the hole's centre
	KeepHoles        // never cut for a hole: pieces may keep holes (reported)
};

struct PolygonOptions
{
	double           tau = 0;   // model units; > 0
	CutLineSelection cut_line_selection = CutLineSelection::Best;
	int              max_parts = 0;         // 0 = unbounded
	int              candidate_lines = 6;   // directions tried inside a notch's cone (Best)
	HoleCut          hole_handling = HoleCut::BestLine;
	HoleOrder        hole_order = HoleOrder::First;
	double           time_limit_seconds = 0;   // 0 = none
	// Called with a percentage and a short status; return false to cancel (throws Error(Cancelled)).
	std::function<bool(int, const char*)> progress;
};

Decomposition2 decompose(const Polygon2& polygon, const PolygonOptions& options);

// Split `p` into exactly two polygons by the cut through `from` (an outer vertex index `vertex`, or -1
// for a point inside a hole) along the line `line`. False if the line cannot split `p` there.
bool separate(const Polygon2& p, const Vec2& from, int vertex, const Vec2& dir, std::array<Polygon2, 2>& out,
              Vec2* cut_from = nullptr, Vec2* cut_to = nullptr);

// A planar polygon given in 3D (a MeshLab layer): the plane's frame and the boundary loops in it.
struct PlanarLoops
{
	Vec3               origin = Vec3::Zero(), u = Vec3::UnitX(), w = Vec3::UnitY(), n = Vec3::UnitZ();
	std::vector<Loop2> loops;
	Vec3               lift(const Vec2& p) const { return origin + p.x() * u + p.y() * w; }
};
using Edge = std::array<int, 2>;

// The boundary loops of a planar triangle mesh (faces given: edges used by one face; its orientation
// sets the plane's normal), or else the closed loops formed by `edges` (every vertex on exactly two).
// The plane is fitted to the vertices used (principal axes; any plane, not only z = 0). Throws
// Error(InvalidInput) if nothing forms a loop, the points are not planar (deviation above 1e-6 of the
// size), a vertex joins more than two boundary edges, or an edge chain is open.
PlanarLoops planar_loops(const std::vector<Vec3>& V, const std::vector<Tri>& F, const std::vector<Edge>& E);

} // namespace acd
