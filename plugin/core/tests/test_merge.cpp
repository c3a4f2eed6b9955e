#include "acd/solid/glue.h"
#include "acd/hull/hull_reach.h"
#include "acd/decompose3/merge.h"
#include "acd/solid/separate.h"
#include "acd/mesh/measures.h"
#include "acd/solid/solid.h"
#include "check.h"
#include "shapes.h"

#include <algorithm>
#include <set>
#include <string>

using namespace acd;

namespace {

using shapes::plane;

SplitOutcome split(const TriMesh& m, const Plane& pl)
{
	SplitOutcome out;
	REQUIRE(separate(m, pl, Vec3(pl.n * pl.d), out));
	return out;
}

// The area of the solid's faces whose corners all have coordinate `axis` equal to `at`.
double area_on(const Solid& u, int axis, double at)
{
	double area = 0;
	for (const Tri& t : u.mesh.F)
		if (u.mesh.V[t[0]][axis] == at && u.mesh.V[t[1]][axis] == at && u.mesh.V[t[2]][axis] == at)
			area += 0.5 * (u.mesh.V[t[1]] - u.mesh.V[t[0]]).cross(u.mesh.V[t[2]] - u.mesh.V[t[0]]).norm();
	return area;
}

// A 40-gon on the unit circle, its corners listed from corner `first` on (so that an ear-clipped cap
// of it is triangulated from there).
std::vector<Eigen::Vector2d> forty_gon(int first)
{
	std::vector<Eigen::Vector2d> out;
	for (int k = 0; k < 40; ++k) {
		const int c = (first + k) % 40;
		out.emplace_back(std::cos(c * M_PI / 20), std::sin(c * M_PI / 20));
	}
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

namespace {

// The two faces of `m` on plane x = `x` (a box's side) re-triangulated along their other diagonal.
void flip_side(TriMesh& m, double x)
{
	std::vector<int> on;
	for (int f = 0; f < (int) m.F.size(); ++f)
		if (std::abs(m.V[m.F[f][0]].x() - x) + std::abs(m.V[m.F[f][1]].x() - x) + std::abs(m.V[m.F[f][2]].x() - x) == 0)
			on.push_back(f);
	REQUIRE(on.size() == 2);
	Tri &s = m.F[on[0]], &t = m.F[on[1]];
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j)
			if (s[i] == t[(j + 1) % 3] && s[(i + 1) % 3] == t[j]) {   // shared edge a -> b in s, b -> a in t
				const int a = s[i], b = s[(i + 1) % 3], c = s[(i + 2) % 3], d = t[(j + 2) % 3];
				s = {a, d, c};
				t = {d, b, c};
				return;
			}
	FAIL("the side's two faces share no edge");
}

} // namespace

TEST_CASE("glue: caps triangulated differently on the two sides cross, and still close exactly")
{
	// Two boxes touching on x = 1 with crossing diagonals there, and a copy of one corner a rounding
	// error away: the seam's triangulation has a crossing vertex, and the near copy is one vertex.
	TriMesh a = shapes::box({0, 0, 0}, {1, 1, 1}), b = shapes::box({1, 0, 0}, {2, 2, 1});
	flip_side(a, 1);
	for (Vec3& p : b.V)
		if (p.x() == 1 && p.y() == 0 && p.z() == 0) p.y() = 1e-17;
	const TriMesh g = glue(a, b, {plane({1, 0, 0}, 1)}, 1e-9);
	const Solid   u = make_solid(g);
	CHECK(u.shells == 1);
	CHECK(u.self_intersections == 0);
	CHECK_NEAR(u.volume, 3.0, 1e-12);
	// The exposed part of b's side (y from 1 to 2) stays, the rest of both sides is gone.
	CHECK_NEAR(area_on(u, 0, 1), 1.0, 1e-12);
}

TEST_CASE("glue: round caps triangulated from different corners cancel, or leave the ring one side covers")
{
	// Two 40-gon prisms meeting at z = 1, their caps fanned from opposite corners (each side's
	// triangulation crosses the other's some 400 times); then a square prism over the 40-gon.
	const std::vector<Eigen::Vector2d> round = forty_gon(0), turned = forty_gon(20);
	const TriMesh a   = shapes::extrude(round, 0, 1);
	const double  vol = signed_volume(a);
	const Solid same = make_solid(glue(a, shapes::extrude(turned, 1, 2), {plane({0, 0, 1}, 1)}, 1e-9));
	CHECK(same.shells == 1);
	CHECK(same.self_intersections == 0);
	CHECK_NEAR(same.volume, 2 * vol, 1e-12);
	CHECK(area_on(same, 2, 1) == 0);
	const std::vector<Eigen::Vector2d> square = {{-1.5, -1.5}, {1.5, -1.5}, {1.5, 1.5}, {-1.5, 1.5}};
	const Solid ring = make_solid(glue(a, shapes::extrude(square, 1, 2), {plane({0, 0, 1}, 1)}, 1e-9));
	CHECK(ring.shells == 1);
	CHECK(ring.self_intersections == 0);
	CHECK_NEAR(ring.volume, vol + 9, 1e-12);
	CHECK_NEAR(area_on(ring, 2, 1), 9 - vol, 1e-12);   // the prism is 1 high: its volume is its cap's area
}

namespace {

// Face (p, q, r) of `m` split at the middle of its edge p -> q into two, and the edge's other face
// (q, p, s) left as it is, closed by a face with no area: p, q and the middle on one line.
void split_with_needle(TriMesh& m, int p, int q)
{
	for (Tri& t : m.F)
		for (int k = 0; k < 3; ++k)
			if (t[k] == p && t[(k + 1) % 3] == q) {
				const int r = t[(k + 2) % 3], mid = (int) m.V.size();
				m.V.push_back(0.5 * (m.V[p] + m.V[q]));
				t = {p, mid, r};
				m.F.push_back({mid, q, r});
				m.F.push_back({p, q, mid});
				return;
			}
	FAIL("no face has the edge");
}

} // namespace

TEST_CASE("glue: a cap face with no area, or one side's faces on the plane turned both ways, still close exactly")
{
	// The 40-gon prism's top cap holds a face with its corners on one line (a cut leaves such faces
	// where it closes a T-junction); the other prism's cap is fanned from the opposite corner.
	const std::vector<Eigen::Vector2d> round = forty_gon(0), turned = forty_gon(20);
	TriMesh      a   = shapes::extrude(round, 0, 1);
	const double vol = signed_volume(a);
	int p = -1, q = -1;   // an edge inside the top cap (vertices 40 to 79, not neighbours on the rim)
	for (const Tri& t : a.F)
		for (int k = 0; k < 3 && p < 0; ++k) {
			const int i = t[k], j = t[(k + 1) % 3];
			if (i >= 40 && j >= 40 && (j - i + 40) % 40 != 1 && (i - j + 40) % 40 != 1) p = i, q = j;
		}
	REQUIRE(p >= 0);
	split_with_needle(a, p, q);
	const Solid same = make_solid(glue(a, shapes::extrude(turned, 1, 2), {plane({0, 0, 1}, 1)}, 1e-9));
	CHECK(same.shells == 1);
	CHECK(same.self_intersections == 0);
	CHECK_NEAR(same.volume, 2 * vol, 1e-12);
	CHECK(area_on(same, 2, 1) == 0);

	// One side two boxes, the first below z = 1 (its top on the plane, turned up), the second above
	// it elsewhere (its bottom on the plane, turned down); the other side a box on the first.
	TriMesh two = shapes::box({0, 0, 0}, {1, 1, 1});
	append(two, shapes::box({2, 0, 1}, {3, 1, 2}));
	const Solid u = make_solid(glue(two, shapes::box({0, 0, 1}, {1, 1, 2}), {plane({0, 0, 1}, 1)}, 1e-9));
	CHECK(u.shells == 2);
	CHECK(u.self_intersections == 0);
	CHECK_NEAR(u.volume, 3.0, 1e-12);
	CHECK_NEAR(area_on(u, 2, 1), 1.0, 1e-12);   // the second box's bottom, all that stays on the plane
}

// Options cutting `m` at tau = `share` of its size, merging off (the leaves, ready to merge).
static DecomposeOptions unmerged(const TriMesh& m, double share)
{
	DecomposeOptions o;
	o.tau         = share * extent(m.V);
	o.merge_parts = false;
	return o;
}

TEST_CASE("merge: neighbours from the caps, and merged parts that are an exact, certified partition")
{
	// A ring: the cuts around it, each made for the notch left most concave, leave neighbouring
	// arcs that are convex enough together.
	const TriMesh    ring = shapes::torus(2, 0.5, 24, 12);
	DecomposeOptions o    = unmerged(ring, 0.05);
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

TEST_CASE("merge: a time limit stops merging and leaves a certified partition")
{
	const TriMesh          ring = shapes::torus(2, 0.5, 24, 12);
	const DecomposeOptions o    = unmerged(ring, 0.05);
	const Decomposition    cut  = decompose(make_solid(ring), o);
	Decomposition       D   = cut;
	// No time left: nothing merges, and the leaves are the parts, each still within tau.
	CHECK(merge_parts(D, o.tau, {}, 1e-9) == 0);
	CHECK(D.merge_time_limit_reached);
	CHECK(D.parts() == cut.parts());
	CHECK(D.tau_convex());
	// Time enough: the same merges as without a limit.
	Decomposition E = cut, F = cut;
	CHECK(merge_parts(E, o.tau, {}, 3600) == merge_parts(F, o.tau));
	CHECK(E.merges > 0);
	CHECK(!E.merge_time_limit_reached);
	CHECK(E.parts().size() == F.parts().size());
	// Progress is heard while the pairs are measured, not only once a pair has merged.
	Decomposition    G = cut;
	std::vector<std::string> said;
	merge_parts(G, o.tau, [&](int, const char* msg) { return said.emplace_back(msg), true; });
	CHECK(std::any_of(said.begin(), said.end(), [](const std::string& m) { return m.find("pairs measured") != std::string::npos; }));
}

TEST_CASE("merge: a memo measures each union once and gives the same parts")
{
	const TriMesh          ring = shapes::torus(2, 0.5, 24, 12);
	const DecomposeOptions o    = unmerged(ring, 0.05);
	const Decomposition    cut  = decompose(make_solid(ring), o);
	Decomposition          plain = cut, first = cut, again = cut;
	merge_parts(plain, o.tau);
	MergeMemo memo;
	merge_parts(first, o.tau, {}, 0, &memo);
	const size_t measured = memo.size();
	CHECK(measured >= cut.leaves().size() - 1);   // every neighbouring pair at least
	merge_parts(again, o.tau, {}, 0, &memo);
	CHECK(memo.size() == measured);   // the same tree again: every union from the memo
	for (const Decomposition* D : {&first, &again}) {
		REQUIRE(D->parts() == plain.parts());
		for (int p : plain.parts()) {
			CHECK(D->nodes[p].mesh.V == plain.nodes[p].mesh.V);
			CHECK(D->nodes[p].mesh.F == plain.nodes[p].mesh.F);
			CHECK(D->nodes[p].concavity == plain.nodes[p].concavity);
			CHECK(D->nodes[p].merged == plain.nodes[p].merged);
		}
	}
	CHECK(plain.merges > 0);
}

TEST_CASE("crossings where parts touch across a cut are no fold; elsewhere they count")
{
	// Two boxes touching on the plane x = 0: their faces there overlap (crossings), on either side of it.
	TriMesh two = shapes::box({-1, 0, 0}, {0, 1, 1});
	append(two, shapes::box({0, 0.25, 0.25}, {1, 0.75, 0.75}));
	const Solid s = make_solid(two);
	REQUIRE(s.self_intersections > 0);
	Plane at0;
	at0.n = Vec3::UnitX(), at0.d = 0;
	CHECK(crossings_off_cuts(s, {at0}, 1e-9) == 0);
	Plane elsewhere = at0;
	elsewhere.d     = 0.5;
	CHECK(crossings_off_cuts(s, {elsewhere}, 1e-9) == s.self_intersections);
	CHECK(crossings_off_cuts(s, {}, 1e-9) == s.self_intersections);
}

namespace {

// Every leaf in exactly one part, pointing to it; each part one closed solid of its leaves' volume,
// within tau, its hull within 1% of tau over every facet (no bridge classification trusted).
void check_partition(const Decomposition& D, double tau)
{
	std::set<int> covered;
	for (int p : D.parts()) {
		const Node&            n      = D.nodes[p];
		const Solid            s      = make_solid(n.mesh);
		const std::vector<int> leaves = n.merged.empty() ? std::vector<int>{p} : n.merged;
		double                 sum    = 0;
		for (int l : leaves) {
			CHECK(covered.insert(l).second);
			CHECK(D.nodes[l].part == (n.merged.empty() ? -1 : p));
			sum += D.nodes[l].volume;
		}
		CHECK(s.shells == 1);
		CHECK_NEAR(s.volume, sum, 1e-9);
		CHECK(n.concavity <= tau);
		const ConvexHull h(s.mesh.V);
		CHECK(hull_reach(s.mesh, h, std::vector<char>(h.facets(), 1), tau, 0.01 * tau, 0.0, 2000000).upper <= 1.01 * tau);
	}
	CHECK(covered.size() == D.leaves().size());
}

// A thin-walled bowl on a foot ring, turned about z: its wall is cut into many arcs that merge.
TriMesh bowl(int segments)
{
	std::vector<Eigen::Vector2d> profile = {{0, 0}, {2, 0}, {2, 0.3}};
	for (int d = 25; d <= 90; d += 5) profile.push_back({5 * std::sin(d * M_PI / 180), 5.3 - 5 * std::cos(d * M_PI / 180)});
	for (int d = 90; d >= 0; d -= 5) profile.push_back({4.6 * std::sin(d * M_PI / 180), 5.3 - 4.6 * std::cos(d * M_PI / 180)});
	return shapes::lathe(profile, segments);
}

std::vector<std::string> part_paths(const Decomposition& D)
{
	std::vector<std::string> out;
	for (int p : D.parts()) out.push_back(D.nodes[p].path);
	return out;
}

} // namespace

TEST_CASE("merge further: from the leaves it is the merge; parts taken apart merge back across the parts as they stand")
{
	const TriMesh    b = bowl(24);
	DecomposeOptions o = unmerged(b, 0.025);
	o.cut_search       = CutSearch::Fast;
	const Decomposition cut = decompose(make_solid(b), o);
	Decomposition       D    = cut;
	const int           m    = merge_parts(D, o.tau);
	REQUIRE(m > 0);

	// From the leaves, every pair measured first: the same parts.
	Decomposition again = cut;
	CHECK(merge_parts_further(again, o.tau, [](int, int) { return true; }) == m);
	CHECK(part_paths(again) == part_paths(D));

	// Two merged parts taken apart, as a search of them again leaves its own parts: their leaves
	// merge again, with each other or with the merged parts around them.
	const size_t          merged = D.parts().size();
	std::vector<char>     drop(D.nodes.size(), 0);
	std::set<std::string> apart;
	int                   taken = 0;
	for (int p : D.parts())
		if (!D.nodes[p].merged.empty() && taken < 2) {
			drop[p] = 1, ++taken;
			D.merges -= (int) D.nodes[p].merged.size() - 1;
			for (int l : D.nodes[p].merged) D.nodes[l].part = -1, apart.insert(D.nodes[l].path);
		}
	REQUIRE(taken == 2);
	drop_nodes(D, drop);
	const size_t before = D.parts().size();
	REQUIRE(before > merged);
	check_partition(D, o.tau);
	// Only the pairs `first` names are measured at the start: none named, none merged.
	Decomposition none = D;
	CHECK(merge_parts_further(none, o.tau, [](int, int) { return false; }) == 0);
	CHECK(none.parts().size() == before);
	const int further = merge_parts_further(D, o.tau, [&](int a, int b) {
		return apart.count(D.nodes[a].path) > 0 || apart.count(D.nodes[b].path) > 0;
	});
	CHECK(further > 0);
	CHECK(D.parts().size() == before - further);
	CHECK(D.parts().size() == D.leaves().size() - D.merges);
	check_partition(D, o.tau);
	// The greedy merge leaves no neighbouring pair whose union passes: merging on finds none.
	const size_t after = D.parts().size();
	CHECK(merge_parts_further(D, o.tau, [](int, int) { return true; }) == 0);
	CHECK(D.parts().size() == after);
}

namespace {

// The distance from p to triangle (a, b, c), by the test's own arithmetic: the plane's foot when it
// lies inside, else the nearest of the three edges.
double to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
	const auto to_segment = [&](const Vec3& s, const Vec3& t) {
		const double u = std::clamp((p - s).dot(t - s) / (t - s).squaredNorm(), 0.0, 1.0);
		return (p - (s + u * (t - s))).norm();
	};
	const Vec3 n = (b - a).cross(c - a).normalized();
	const Vec3 f = p - n * n.dot(p - a);
	const bool inside = (b - a).cross(f - a).dot(n) >= 0 && (c - b).cross(f - b).dot(n) >= 0 && (a - c).cross(f - c).dot(n) >= 0;
	return inside ? std::abs(n.dot(p - a)) : std::min({to_segment(a, b), to_segment(b, c), to_segment(c, a)});
}

// How far the hull of `m` reaches beyond it, from points spread over the hull's triangles (`steps` per
// edge), plus the farthest any hull point lies from its nearest sample: no hull point is farther.
// `spacing` gets that last term (the samples alone reach no farther than the hull).
double hull_reach_sampled(const TriMesh& m, int steps, double* spacing_out = nullptr)
{
	const ConvexHull h(m.V);
	double           reach = 0, spacing = 0;
	for (const Tri& t : h.triangles) {
		const Vec3 &a = h.points[t[0]], &b = h.points[t[1]], &c = h.points[t[2]];
		spacing = std::max({spacing, (b - a).norm() / steps, (c - b).norm() / steps, (a - c).norm() / steps});
		for (int i = 0; i <= steps; ++i)
			for (int j = 0; i + j <= steps; ++j) {
				const Vec3 p    = a + (b - a) * (double(i) / steps) + (c - a) * (double(j) / steps);
				double     near = INFINITY;
				for (const Tri& f : m.F) near = std::min(near, to_triangle(p, m.V[f[0]], m.V[f[1]], m.V[f[2]]));
				reach = std::max(reach, near);
			}
	}
	if (spacing_out) *spacing_out = spacing;
	return reach + spacing;
}

} // namespace

TEST_CASE("merge by hull distance: a slot narrower than tau stays in one part, its hull within tau")
{
	// A block with a slot 0.2 wide and 1.6 deep: the slot's floor lies 1.6 below the hull's lid, but
	// the lid lies no more than 0.1 from the slot's walls.
	const TriMesh    block = shapes::extrude(shapes::slot_shape(), 0, 1);
	DecomposeOptions o     = unmerged(block, 0.05);
	REQUIRE((o.tau > 0.1 && o.tau < 1.6));
	const Decomposition cut = decompose(make_solid(block), o);
	Decomposition       by_hull = cut, by_notches = cut;
	merge_parts(by_hull, o.tau, {}, 0, nullptr, MergeMeasure::HullDistance);
	merge_parts(by_notches, o.tau, {}, 0, nullptr, MergeMeasure::Concavity);
	MESSAGE(cut.leaves().size() << " leaves: " << by_hull.parts().size() << " parts by the hull, " << by_notches.parts().size() << " by the notches");
	CHECK(by_hull.parts().size() < by_notches.parts().size());
	CHECK(by_hull.tau_convex());
	CHECK(by_notches.tau_convex());
	int hull_only = 0;
	for (int p : by_hull.parts()) {
		const Node& n = by_hull.nodes[p];
		CHECK(hull_reach_sampled(n.mesh, 40) <= 1.01 * o.tau);
		if (!n.hull_certified) continue;
		++hull_only;
		CHECK(!n.merged.empty());
		CHECK(n.concavity > o.tau);   // the slot's floor, as the cuts measure it
	}
	CHECK(hull_only > 0);
	for (int p : by_notches.parts()) CHECK((by_notches.nodes[p].concavity <= o.tau && !by_notches.nodes[p].hull_certified));
}

TEST_CASE("merge: a union's hull reach is measured once it comes first in line, not for every union; a union "
          "whose reach is over tau never merges")
{
	// Six cubes in a row, 0.01 apart: one hull stands for any run of them within tau. Each merge makes
	// the pairs measured with its two parts moot, and their reaches are never measured.
	TriMesh row = shapes::box(Vec3(0, 0, 0), Vec3(1, 1, 1));
	for (int k = 1; k < 6; ++k) row = shapes::merge(row, shapes::box(Vec3(1.01 * k, 0, 0), Vec3(1.01 * k + 1, 1, 1)));
	const DecomposeOptions o = unmerged(row, 0.02);
	Decomposition          D = decompose(make_solid(row), o);
	MergeMemo              memo;
	merge_parts(D, o.tau, {}, 0, &memo);
	MESSAGE(D.merges << " merges, " << memo.size() << " unions measured, " << memo.candidates()
	                 << " within tau but for the reach, " << memo.reaches() << " reaches");
	CHECK(D.merges == 5);
	REQUIRE(D.parts().size() == 1);
	CHECK(memo.reaches() >= (size_t) D.merges);   // every merged union's, at least
	CHECK(memo.reaches() < memo.candidates());
	CHECK(hull_reach_sampled(D.nodes[D.parts()[0]].mesh, 80) <= 1.01 * o.tau);

	// A ring cut short at 1%: neighbouring arcs are within tau by their notches, but the hull of two
	// spans the hole farther than tau from them (re-measured on one pair). None merges.
	const TriMesh          ring = shapes::torus(2, 0.5, 24, 12);
	const DecomposeOptions r    = unmerged(ring, 0.01);
	Decomposition          R    = decompose(make_solid(ring), r);
	MergeMemo              rmemo;
	merge_parts(R, r.tau, {}, 0, &rmemo);
	CHECK(rmemo.candidates() > 0);
	CHECK(R.merges == 0);
	CHECK(R.parts() == R.leaves());
	const std::vector<LeafContact> contacts = neighbouring_leaves(R);
	REQUIRE(!contacts.empty());
	TriMesh two = R.nodes[contacts[0].a].mesh;
	append(two, R.nodes[contacts[0].b].mesh);
	double       spacing = 0;
	const double bound   = hull_reach_sampled(two, 20, &spacing);
	CHECK(bound - spacing > 1.01 * r.tau);
}

TEST_CASE("under the hull distance measure a part whose hull stays within tau is not cut")
{
	// The slotted block at the same tau: its hull lies within tau of it, so the cuts stop at the root
	// (one part, no merge needed); held to every notch, its slot is cut apart.
	const TriMesh    block = shapes::extrude(shapes::slot_shape(), 0, 1);
	DecomposeOptions o     = unmerged(block, 0.05);
	o.merge_parts          = true;
	const Decomposition by_hull = decompose(make_solid(block), o);
	o.merge_measure             = MergeMeasure::Concavity;
	const Decomposition by_notches = decompose(make_solid(block), o);
	MESSAGE(by_hull.nodes.size() << " nodes by the hull, " << by_notches.parts().size() << " parts by the notches");
	REQUIRE(by_hull.parts().size() == 1);
	CHECK(by_hull.nodes.size() == 1);
	CHECK(by_hull.merges == 0);
	CHECK(by_hull.tau_convex());
	const Node& root = by_hull.nodes[0];
	CHECK(root.hull_certified);
	CHECK(root.concavity > o.tau);
	CHECK(hull_reach_sampled(root.mesh, 40) <= 1.01 * o.tau);
	CHECK(by_notches.parts().size() > 1);
	// Not cut on its notches alone: with the merge off the cut tree is the paper's.
	o.merge_measure = MergeMeasure::HullDistance;
	o.merge_parts   = false;
	CHECK(decompose(make_solid(block), o).leaves().size() > 1);
}

TEST_CASE("merge by hull distance: parts of separate solids merge where one hull stands for both within tau")
{
	// An assembly of two blocks, the second a little smaller and off the first's axis, a gap between
	// them along x. Their hull spans the gap: its farthest point from the blocks lies half the gap (or
	// more) away.
	for (const double gap : {0.1, 0.6}) {
		TriMesh two = shapes::box({0, 0, 0}, {1, 1, 1});
		append(two, shapes::box({1 + gap, 0.05, 0}, {1.8 + gap, 0.95, 0.95}));
		const Solid      solid = make_solid(two);
		DecomposeOptions o;
		o.tau = 0.05 * extent(two.V);
		REQUIRE((o.tau > 0.05 && o.tau < 0.3));
		const Decomposition D = decompose(solid, o);
		const double        volume = 1.0 + 0.8 * 0.9 * 0.95;
		CHECK(D.tau_convex());
		if (gap < o.tau) {   // near: one hull within tau of both blocks
			REQUIRE(D.parts().size() == 1);
			const Node& part = D.nodes[D.parts()[0]];
			CHECK(part.mesh.F.size() == two.F.size());
			CHECK(std::abs(signed_volume(part.mesh) - volume) < 1e-9);
			CHECK(hull_reach_sampled(part.mesh, 40) <= 1.01 * o.tau);
			// By the paper's measure alone the two blocks stay apart.
			o.merge_measure = MergeMeasure::Concavity;
			CHECK(decompose(solid, o).parts().size() == 2);
		}
		else {   // far: the gap's middle lies farther than tau from both
			CHECK(D.parts().size() == 2);
			CHECK(hull_reach_sampled(two, 10) > 1.01 * o.tau);
		}
	}
}
