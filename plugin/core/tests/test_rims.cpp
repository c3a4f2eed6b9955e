#include "acd/solid/rims.h"
#include "check.h"

#include <algorithm>
#include <set>
#include <utility>

using namespace acd;

namespace {

// Directed edges used one way only, counted here (not by the core).
int unmatched(const TriMesh& m)
{
	std::multiset<std::pair<int, int>> e;
	for (const Tri& t : m.F)
		for (int k = 0; k < 3; ++k) e.insert({t[k], t[(k + 1) % 3]});
	int n = 0;
	for (const auto& [a, b] : e) n += !e.count({b, a});
	return n;
}

// The fan of triangles below edge 0 -> 1 (from 0 at x = 0 to 1 at x = 1), split at the points `at`
// (x in (0, 1)), closed with face (0, 1, top) above: a T-junction at each split point. The points get
// ids 3.., in the order given; `lift` raises them off the edge by that much.
TriMesh split_edge(const std::vector<double>& at, double lift = 0)
{
	TriMesh m;
	m.V = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}};   // 0, 1, top (2)
	for (double x : at) m.V.push_back({x, lift, 0});
	m.V.push_back({0.5, -1, 0});   // below
	const int below = (int) m.V.size() - 1;
	std::vector<int> chain = {0};
	std::vector<int> order(at.size());
	for (size_t i = 0; i < at.size(); ++i) order[i] = (int) i;
	std::sort(order.begin(), order.end(), [&](int a, int b) { return at[a] < at[b]; });
	for (int i : order) chain.push_back(3 + i);
	chain.push_back(1);
	m.F.push_back({0, 1, 2});
	for (size_t i = 0; i + 1 < chain.size(); ++i) m.F.push_back({chain[i + 1], chain[i], below});
	return m;
}

} // namespace

TEST_CASE("close_rims: a face over a split edge is fanned out at the split points, the nearest first")
{
	TriMesh one = split_edge({0.4});
	CHECK(unmatched(one) == 3 + 4);   // 0 -> 1 against 1 -> 3 -> 0, and the open outline's four edges
	close_rims(one, 1e-9);
	CHECK(one.F.size() == 4);
	CHECK(std::count(one.F.begin(), one.F.end(), Tri{0, 3, 2}) == 1);
	CHECK(std::count(one.F.begin(), one.F.end(), Tri{3, 1, 2}) == 1);
	CHECK(unmatched(one) == 4);   // only the outline is left open

	// Three points, given out of order: each pass takes the one nearest to the edge's start.
	TriMesh three = split_edge({0.7, 0.2, 0.45});
	close_rims(three, 1e-9);
	CHECK(three.F.size() == 4 + 4);
	CHECK(unmatched(three) == 4);
	for (const Tri& t : {Tri{0, 4, 2}, Tri{4, 5, 2}, Tri{5, 3, 2}, Tri{3, 1, 2}})
		CHECK(std::count(three.F.begin(), three.F.end(), t) == 1);
}

TEST_CASE("close_rims: points off the edge by more than eps, or past its ends, are left alone")
{
	TriMesh off = split_edge({0.5}, 1e-6);
	close_rims(off, 1e-7);
	CHECK(off.F.size() == 3);
	TriMesh within = split_edge({0.5}, 1e-8);
	close_rims(within, 1e-7);
	CHECK(within.F.size() == 4);
	// A rim running along y only (every rim point at the same x): the same, whichever axis it lies on.
	TriMesh turned = split_edge({0.3, 0.6});
	for (Vec3& p : turned.V) p = Vec3(2.0, p.x(), p.y());
	close_rims(turned, 1e-9);
	CHECK(turned.F.size() == 3 + 3);
	CHECK(unmatched(turned) == 4);
}
