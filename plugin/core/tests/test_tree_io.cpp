#include "acd/io/tree_io.h"
#include "acd/mesh/measures.h"
#include "acd/solid/solid.h"
#include "shapes.h"
#include "check.h"

#include <nlohmann/json.hpp>

using namespace acd;

TEST_CASE("a tree survives a round trip through json")
{
	DecomposeOptions o;
	o.tau                  = 0.01;
	const Decomposition D  = decompose(make_solid(shapes::extrude(shapes::u_shape(), 0, 1)), o);
	const std::string   js = tree_to_json(D, true);
	CHECK(nlohmann::json::parse(js).at("schema").get<int>() == kTreeSchema);
	std::vector<TriMesh> hulls;
	const Decomposition  R = tree_from_json(js, &hulls);
	CHECK((R.nodes.size() == D.nodes.size() && hulls.size() == D.nodes.size()));
	CHECK(R.tau == D.tau);
	for (size_t i = 0; i < D.nodes.size(); ++i) {
		const Node &a = D.nodes[i], &b = R.nodes[i];
		CHECK((a.path == b.path && a.parent == b.parent && a.child[0] == b.child[0] && a.child[1] == b.child[1]));
		CHECK((a.concavity == b.concavity && a.volume == b.volume && a.has_plane == b.has_plane));
		if (a.has_plane) CHECK((a.plane.n == b.plane.n && a.plane.d == b.plane.d));   // doubles written exactly
		if (a.leaf()) CHECK((a.mesh.V == b.mesh.V && a.mesh.F == b.mesh.F));
		CHECK(!hulls[i].F.empty());
	}
	CHECK(R.leaves() == D.leaves());
}

TEST_CASE("a part merged by its hull alone is marked so in the tree file")
{
	// The slotted block at tau 5% of its size merges into one part whose notches lie deeper than tau.
	const TriMesh    block = shapes::extrude(shapes::slot_shape(), 0, 1);
	DecomposeOptions o;
	o.tau                 = 0.05 * extent(block.V);
	const Decomposition D = decompose(make_solid(block), o);
	const Decomposition R = tree_from_json(tree_to_json(D, true));
	int                 marked = 0;
	REQUIRE(R.nodes.size() == D.nodes.size());
	for (size_t i = 0; i < D.nodes.size(); ++i) {
		CHECK(R.nodes[i].hull_certified == D.nodes[i].hull_certified);
		marked += D.nodes[i].hull_certified;
	}
	CHECK(marked == 1);
	CHECK(D.tau_convex());
}

TEST_CASE("a broken tree file is refused with the reason")
{
	auto refused = [](const std::string& text, const std::string& why) {
		try {
			tree_from_json(text);
		}
		catch (const Error& e) {
			return e.kind == Error::InvalidInput && std::string(e.what()).find(why) != std::string::npos;
		}
		return false;
	};
	CHECK(refused("{not json", "not valid JSON"));
	CHECK(refused("{\"polygons\": []}", "no nodes"));
	CHECK(refused("{\"schema\": 99, \"nodes\": [{}]}", "newer"));
	CHECK(refused("{\"nodes\": [{\"children\": [5, 6]}]}", "broken links"));
	CHECK(refused("{\"nodes\": [{\"children\": [-1, -1]}]}", "no part geometry"));
	CHECK(refused("{\"nodes\": [{\"children\": [-1, -1], \"mesh\": {\"v\": [0, 0, 0], \"f\": [0, 0, 3]}}]}", "bad vertex"));
}
