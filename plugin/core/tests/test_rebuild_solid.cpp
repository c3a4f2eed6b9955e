#include "acd/decompose3/decompose.h"
#include "acd/structure/level_of_detail.h"
#include "acd/mesh/measures.h"
#include "acd/solid/solid.h"
#include "check.h"
#include "shapes.h"

using namespace acd;

namespace {

Decomposition run(const TriMesh& m, double tau)
{
	DecomposeOptions o;
	o.tau         = tau;
	o.merge_parts = false;   // the cut tree alone
	return decompose(make_solid(m), o);
}

double leaves_below(const Decomposition& D, int id)
{
	const Node& n = D.nodes[id];
	return n.leaf() ? n.volume : leaves_below(D, n.child[0]) + leaves_below(D, n.child[1]);
}

} // namespace

TEST_CASE("every node rebuilt from its leaves is a closed solid of their volume")
{
	const TriMesh       plus = shapes::extrude(shapes::plus_shape(), 0, 1);
	const Decomposition D    = run(plus, 0.01);
	REQUIRE(D.leaves().size() >= 3);
	for (int id = 0; id < (int) D.nodes.size(); ++id) {
		const TriMesh r = rebuild_solid(D, id);
		const Solid   s = make_solid(r);   // closed, manifold, outward, or it throws
		CHECK(s.shells == 1);
		CHECK_NEAR(s.volume, leaves_below(D, id), 1e-9);
		CHECK_NEAR(s.volume, D.nodes[id].volume, 1e-9);
	}
	CHECK_NEAR(make_solid(rebuild_solid(D, 0)).volume, signed_volume(plus), 1e-9);
}

TEST_CASE("a leaf rebuilt is the leaf itself")
{
	const Decomposition D = run(shapes::extrude(shapes::l_shape(), 0, 1), 0.01);
	for (int l : D.leaves()) CHECK(rebuild_solid(D, l).F.size() == D.nodes[l].mesh.F.size());
}

TEST_CASE("level of detail by tau and by depth")
{
	const Decomposition D = run(shapes::extrude(shapes::plus_shape(), 0, 1), 0.01);
	CHECK(level_of_detail(D, 0.01).size() == D.leaves().size());
	CHECK(level_of_detail(D, 100.0) == std::vector<int>{0});
	CHECK(level_of_detail(D, 0.01, 0) == std::vector<int>{0});
	CHECK(level_of_detail(D, 0.01, 1).size() == 2);
}
