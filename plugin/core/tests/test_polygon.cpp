#include "acd/polygon/polygon.h"
#include "check.h"

using namespace acd;

namespace {

Decomposition2 run(const std::vector<Loop2>& loops, double tau, CutLineSelection sel = CutLineSelection::Best,
                   HoleCut holes = HoleCut::BestLine)
{
	PolygonOptions o;
	o.tau                = tau;
	o.cut_line_selection = sel;
	o.hole_handling      = holes;
	return decompose(polygons_from_loops(loops).at(0), o);
}

double leaf_area(const Decomposition2& d)
{
	double a = 0;
	for (int i : d.leaves()) a += area(d.nodes[i].polygon);
	return a;
}

} // namespace

TEST_CASE("an L polygon is two convex pieces")
{
	const Loop2 L = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
	for (auto sel : {CutLineSelection::Bisector, CutLineSelection::Best}) {
		const Decomposition2 d = run({L}, 0.01, sel);
		CHECK(d.leaves().size() == 2);
		CHECK_NEAR(leaf_area(d), 3.0, 1e-12);
		for (int i : d.leaves()) CHECK(measure_concavity(d.nodes[i].polygon).notches == 0);
	}
}

TEST_CASE("a square with a hole is cut through the hole into pieces without holes")
{
	const Loop2 outer = {{0, 0}, {4, 0}, {4, 4}, {0, 4}}, hole = {{1.5, 1.5}, {2.5, 1.5}, {2.5, 2.5}, {1.5, 2.5}};
	const Decomposition2 d = run({outer, hole}, 0.05);
	CHECK(d.hole_cuts >= 1);
	CHECK_NEAR(leaf_area(d), 15.0, 1e-9);
	for (int i : d.leaves()) {
		CHECK(d.nodes[i].polygon.holes.empty());
		CHECK(d.nodes[i].concavity <= 0.05);
	}
	const Decomposition2 kept = run({outer, hole}, 0.05, CutLineSelection::Best, HoleCut::KeepHoles);
	CHECK(kept.leaves().size() == 1);
	CHECK(kept.kept_holes == 1);
}

TEST_CASE("a comb's teeth become pieces and max_parts bounds them")
{
	// base 9 x 1, five teeth 1 wide and 2 high, gaps 1 wide
	const Loop2 comb = {{0, 0}, {9, 0}, {9, 3}, {8, 3}, {8, 1}, {7, 1}, {7, 3}, {6, 3}, {6, 1}, {5, 1},
	                    {5, 3}, {4, 3}, {4, 1}, {3, 1}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
	const Decomposition2 d = run({comb}, 0.01);
	CHECK(d.leaves().size() >= 5);
	CHECK_NEAR(leaf_area(d), 19.0, 1e-9);
	CHECK(d.max_leaf_concavity() <= 0.01);
	PolygonOptions o;
	o.tau       = 0.01;
	o.max_parts = 3;
	const Decomposition2 bounded = decompose(polygons_from_loops({comb}).at(0), o);
	CHECK(bounded.leaves().size() == 3);
	CHECK(bounded.max_parts_reached);
	CHECK_NEAR(leaf_area(bounded), leaf_area(d), 1e-9);
}
