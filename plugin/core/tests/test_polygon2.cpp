#include "acd/mesh/polygon2.h"
#include "acd/mesh/measures.h"
#include "check.h"

using namespace acd;

static double triangles_area(const std::vector<Vec2>& V, const std::vector<Tri>& F)
{
	double a = 0;
	for (const Tri& t : F) {
		const Vec2 u = V[t[1]] - V[t[0]], w = V[t[2]] - V[t[0]];
		a += 0.5 * (u.x() * w.y() - u.y() * w.x());   // counter-clockwise: positive
	}
	return a;
}

TEST_CASE("a square with a hole triangulates to its area")
{
	Polygon2 p;
	p.outer = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
	p.holes = {{{1, 1}, {1, 3}, {3, 3}, {3, 1}}};   // clockwise
	CHECK_NEAR(area(p), 16 - 4, 1e-12);
	CHECK((inside(p.outer, Vec2(0.5, 0.5)) && !inside(p.outer, Vec2(5, 1))));
	CHECK(inside(p.holes[0], Vec2(2, 2)));
	std::vector<Vec2> V;
	std::vector<Tri>  F;
	CHECK(triangulate(p, V, F));
	CHECK(V.size() == 8);
	CHECK_NEAR(triangles_area(V, F), 12, 1e-12);   // the hole is left out, every triangle counter-clockwise
	for (const Tri& t : F) {
		const Vec2 c = (V[t[0]] + V[t[1]] + V[t[2]]) / 3;
		CHECK(!inside(p.holes[0], c));
	}
}

TEST_CASE("orientation of the loops does not matter but crossing loops fail")
{
	Polygon2 p;
	p.outer = {{0, 0}, {0, 4}, {4, 4}, {4, 0}};   // clockwise outer: inside still decided by nesting
	std::vector<Vec2> V;
	std::vector<Tri>  F;
	CHECK(triangulate(p, V, F));
	CHECK_NEAR(triangles_area(V, F), 16, 1e-12);
	p.holes = {{{3, 1}, {5, 1}, {5, 3}, {3, 3}}};   // pokes out through the outer loop
	CHECK(!triangulate(p, V, F));
}
