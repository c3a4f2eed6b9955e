#include "acd/glue.h"
#include "acd/merge.h"
#include "acd/separate.h"
#include "check.h"
#include "shapes.h"

#include <set>

using namespace acd;

namespace {

using shapes::plane;

SplitOutcome split(const TriMesh& m, const Plane& pl)
{
	SplitOutcome out;
	REQUIRE(separate(m, pl, Vec3(pl.n * pl.d), out));
	return out;
}

} // namespace

TEST_CASE("glue: two parts whose caps overlap in part become one closed solid of both volumes")
{
	// A bar cut at x = 1; the right half cut again at an angle, so each piece's cap covers only part
	// of the left half's cap.
	const TriMesh      bar   = shapes::box({0, 0, 0}, {2, 1, 1});
	const SplitOutcome halves = split(bar, plane({1, 0, 0}, 1));
	const SplitOutcome right = split(halves.parts[1], plane({0.3, 1, 0.2}, 0.5));
	for (int s = 0; s < 2; ++s) {
		const TriMesh g = glue(halves.parts[0], right.parts[s], {halves.plane}, 1e-9);
		const Solid   u = make_solid(g);   // closed, manifold and outward, or it throws
		CHECK(u.shells == 1);
		CHECK(u.self_intersections == 0);
		CHECK_NEAR(u.volume, signed_volume(halves.parts[0]) + signed_volume(right.parts[s]), 1e-9);
	}
	// Both pieces back onto the left half: the bar again.
	const TriMesh one  = glue(halves.parts[0], right.parts[0], {halves.plane}, 1e-9);
	const TriMesh all  = glue(one, right.parts[1], {halves.plane, right.plane}, 1e-9);
	const Solid   back = make_solid(all);
	CHECK(back.shells == 1);
	CHECK_NEAR(back.volume, 2.0, 1e-9);
}

TEST_CASE("merge: neighbours from the caps, and merged parts that are an exact, certified partition")
{
	// A ring: the cuts around it, each made for the notch left most concave, leave neighbouring
	// arcs that are convex enough together.
	const TriMesh    ring = shapes::torus(2, 0.5, 24, 12);
	DecomposeOptions o;
	o.tau = 0.05 * extent(ring.V);
	o.merge_parts = false;
	const Decomposition cut = decompose(make_solid(ring), o);
	o.merge_parts           = true;
	const Decomposition D   = decompose(make_solid(ring), o);

	// The cut tree is the same with and without the merge; merged parts are extra nodes.
	REQUIRE(D.leaves() == cut.leaves());
	const std::vector<LeafContact> contacts = neighbouring_leaves(cut);
	CHECK(contacts.size() >= cut.leaves().size() - 1);   // the parts of a connected solid touch
	for (const LeafContact& c : contacts) CHECK((cut.nodes[c.a].leaf() && cut.nodes[c.b].leaf() && cut.nodes[c.cut].has_plane));

	CHECK(D.merges > 0);
	CHECK(D.parts().size() == cut.leaves().size() - D.merges);
	CHECK(D.tau_convex());
	double           total = 0;
	std::set<int>    covered;
	for (int p : D.parts()) {
		const Node& n = D.nodes[p];
		const Solid s = make_solid(n.mesh);
		CHECK(s.shells == 1);
		CHECK(n.concavity <= o.tau);
		total += s.volume;
		const std::vector<int> leaves = n.merged.empty() ? std::vector<int>{p} : n.merged;
		double                 sum    = 0;
		for (int l : leaves) {
			CHECK(covered.insert(l).second);   // every leaf in one part
			CHECK(D.nodes[l].part == (n.merged.empty() ? -1 : p));
			sum += D.nodes[l].volume;
		}
		CHECK_NEAR(s.volume, sum, 1e-9);
	}
	CHECK(covered.size() == D.leaves().size());
	CHECK_NEAR(total, signed_volume(ring), 1e-9);
}
