#include "acd/decompose3/measure_memo.h"
#include "acd/mesh/measures.h"
#include "acd/mesh/parallel.h"
#include "acd/solid/solid.h"
#include "check.h"
#include "shapes.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>

using namespace acd;

namespace {

// A U-shaped bar, finely triangulated: several cuts, each with several candidate planes.
Solid fine_u()
{
	TriMesh m = shapes::extrude(shapes::u_shape(), -0.5, 0.5);
	for (int round = 0; round < 2; ++round) m = shapes::subdivided(m);
	return make_solid(m);
}

DecomposeOptions options(double tau, PickRule rule)
{
	DecomposeOptions o;
	o.tau       = tau;
	o.pick_rule = rule;
	return o;
}

void check_same_tree(const Decomposition& a, const Decomposition& b)
{
	REQUIRE(a.nodes.size() == b.nodes.size());
	for (size_t i = 0; i < a.nodes.size(); ++i) {
		CHECK(a.nodes[i].mesh.V == b.nodes[i].mesh.V);
		CHECK(a.nodes[i].mesh.F == b.nodes[i].mesh.F);
		CHECK(a.nodes[i].concavity == b.nodes[i].concavity);
		CHECK(a.nodes[i].hull_distance == b.nodes[i].hull_distance);
	}
}

} // namespace

TEST_CASE("measure memo: searches of one solid that share measures make the trees they make alone")
{
	const Solid  s   = fine_u();
	const double tau = 0.01 * extent(s.mesh.V);
	MeasureMemo  memo;
	const Decomposition first = cut_tree(s, options(tau, PickRule::WorseHalf), nullptr, &memo);
	check_same_tree(first, cut_tree(s, options(tau, PickRule::WorseHalf)));
	REQUIRE(first.parts().size() > 2);
	const size_t kept = memo.size(), hits = memo.hits();
	CHECK(kept > first.nodes.size());   // every candidate's parts, not only the nodes

	// The second rule tries the same planes at the nodes the trees share: those measures are taken.
	const Decomposition second = cut_tree(s, options(tau, PickRule::PartsNeeded), nullptr, &memo);
	check_same_tree(second, cut_tree(s, options(tau, PickRule::PartsNeeded)));
	CHECK(memo.hits() > hits);

	// Another tau measures anew: the same tree as without the memo.
	const Decomposition finer = cut_tree(s, options(0.5 * tau, PickRule::WorseHalf), nullptr, &memo);
	check_same_tree(finer, cut_tree(s, options(0.5 * tau, PickRule::WorseHalf)));
}

TEST_CASE("measure memo: keeps measures only within its budget of faces")
{
	const Solid s = fine_u();
	Node        n;
	n.mesh    = s.mesh;
	int  made = 0;
	auto make = [&] {
		++made;
		return measure_node(n, false, 0.05);
	};
	MeasureMemo small(s.mesh.F.size() - 1), large(s.mesh.F.size());
	small.find_or_make(s.mesh, 0.05, false, make);
	small.find_or_make(s.mesh, 0.05, false, make);
	CHECK(made == 2);
	CHECK(small.size() == 0);
	const MeasuredPtr a = large.find_or_make(s.mesh, 0.05, false, make);
	const MeasuredPtr b = large.find_or_make(s.mesh, 0.05, false, make);
	CHECK(made == 3);
	CHECK(a == b);
	CHECK(large.hits() == 1);
	large.find_or_make(s.mesh, 0.05, true, make);   // the cavity option is part of the key
	CHECK(made == 4);
	large.find_or_make(s.mesh, 0.025, false, make);   // and tau
	CHECK(made == 5);
}

TEST_CASE("measure memo: a measure one thread is making is waited for on another, not made twice")
{
	const Solid s = fine_u();
	Node        n;
	n.mesh = s.mesh;
	MeasureMemo       memo;
	std::atomic<int>  made{0};
	std::vector<char> work(64, 0);
	auto              make = [&] {
        ++made;
        // Until the other thread has found this measure in flight (bounded: a memo that does not share
        // measures in flight never lets it find one, and then both make it).
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
        while (memo.hits() == 0 && std::chrono::steady_clock::now() < until) std::this_thread::yield();
        parallel_for(work.size(), [&](size_t i) { work[i] = 1; });   // a loop the waiting thread may join
        return measure_node(n, false, 0.05);
	};
	MeasuredPtr a, b;
	std::thread maker([&] { a = memo.find_or_make(s.mesh, 0.05, false, make); });
	while (made == 0) std::this_thread::yield();
	b = memo.find_or_make(s.mesh, 0.05, false, make);
	maker.join();
	CHECK(made == 1);
	CHECK(memo.hits() == 1);
	REQUIRE(a);
	CHECK(a == b);
	CHECK(std::count(work.begin(), work.end(), 1) == (long) work.size());
}
