// The merge stage (merge.h): neighbours from the cuts' caps, each neighbouring pair's union scored by
// the cuts' own certificate, the least concave union merged first.
#include "acd/decompose3/merge.h"
#include "acd/solid/glue.h"
#include "acd/hull/hull_reach.h"
#include "acd/hull/hull_traits.h"
#include "acd/mesh/parallel.h"
#include "acd/mesh/content_hash.h"
#include "acd/mesh/measures.h"
#include "acd/solid/solid.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <array>
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <queue>
#include <set>
#include <thread>

namespace acd {

namespace {

using Tri2 = std::array<Eigen::Vector2d, 3>;

// The vertices of the points' convex hull (far fewer than a part's, so the hull of two parts' unions
// is quick to build from them).
std::vector<Vec3> extreme_points(const std::vector<Vec3>& pts)
{
	using K = CGAL::Exact_predicates_inexact_constructions_kernel;
	std::vector<K::Point_3> in, out;
	for (const Vec3& p : pts) in.emplace_back(p.x(), p.y(), p.z());
	CGAL::extreme_points_3(in, std::back_inserter(out), HullTraits());
	std::vector<Vec3> e;
	for (const K::Point_3& p : out) e.emplace_back(p.x(), p.y(), p.z());
	std::sort(e.begin(), e.end(), [](const Vec3& a, const Vec3& b) { return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3); });
	return e;
}

// The faces of `m` lying on plane `pl` (within eps), in the plane's frame (u, w).
std::vector<Tri2> cap_on(const TriMesh& m, const Plane& pl, const Vec3& u, const Vec3& w, double eps)
{
	std::vector<Tri2> out;
	for (const Tri& t : m.F) {
		if (!pl.holds(m.V, t, eps)) continue;
		Tri2 q;
		for (int k = 0; k < 3; ++k) q[k] = {u.dot(m.V[t[k]]), w.dot(m.V[t[k]])};
		out.push_back(q);
	}
	return out;
}

// Two triangles of one plane share area: no edge direction of either separates them by less than
// `margin` of overlap (triangles meeting at an edge or a corner do not).
bool overlap(const Tri2& a, const Tri2& b, double margin)
{
	for (const Tri2* t : {&a, &b})
		for (int k = 0; k < 3; ++k) {
			const Eigen::Vector2d e = (*t)[(k + 1) % 3] - (*t)[k];
			const Eigen::Vector2d n = Eigen::Vector2d(-e.y(), e.x());
			if (!(n.norm() > 0)) return false;
			double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
			for (int s = 0; s < 2; ++s)
				for (const Eigen::Vector2d& p : s ? b : a) {
					const double x = n.dot(p) / n.norm();
					lo[s] = std::min(lo[s], x), hi[s] = std::max(hi[s], x);
				}
			if (std::min(hi[0], hi[1]) - std::max(lo[0], lo[1]) <= margin) return false;
		}
	return true;
}

bool caps_overlap(const std::vector<Tri2>& a, const std::vector<Tri2>& b, double margin)
{
	for (const Tri2& s : a)
		for (const Tri2& t : b)
			if (overlap(s, t, margin)) return true;
	return false;
}

std::vector<int> leaves_below(const Decomposition& D, int id)
{
	std::vector<int> out, stack{id};
	while (!stack.empty()) {
		const Node& n = D.nodes[stack.back()];
		const int   k = stack.back();
		stack.pop_back();
		if (n.leaf()) out.push_back(k);
		else stack.insert(stack.end(), {n.child[1], n.child[0]});
	}
	return out;
}

std::uint64_t planes_hash(const std::vector<Plane>& planes)
{
	std::uint64_t h = planes.size();
	for (const Plane& p : planes) {
		const double w[4] = {p.n.x(), p.n.y(), p.n.z(), p.d};
		h = mix(h, w, sizeof w);
	}
	return h;
}

// The ends of the solid's reflex edges, each once.
std::vector<Vec3> notch_points(const TriMesh& m, const Topology& topo)
{
	std::vector<int> ends;
	for (int f = 0; f < (int) m.F.size(); ++f)
		for (int k = 0; k < 3; ++k)
			if (topo.neighbour[f][k] > f && is_reflex(m, topo, f, k)) ends.insert(ends.end(), {m.F[f][k], m.F[f][(k + 1) % 3]});
	std::sort(ends.begin(), ends.end());
	ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
	std::vector<Vec3> out;
	for (int v : ends) out.push_back(m.V[v]);
	return out;
}

// A part while merging: the leaves it unites, its solid and its measures.
struct Group
{
	std::vector<int>  leaves;    // node ids, path order
	std::uint64_t     content = 0;   // its solid's vertices and faces, hashed (MergeMemo's key)
	Node              part;      // its solid and measures, as the merged part's node will hold them
	std::vector<Vec3> extreme;   // the vertices of its hull
	std::vector<Vec3> notches;   // the ends of its reflex edges (MergeMeasure::Concavity's prefilter only)
	long              crossings = -1;  // faces crossing away from the cuts between its leaves (-1: not counted)
	int               shells = 1;      // its solid's shells (a union across the input's solids has several)
	bool              alive = true;
	int               origin = -1;   // the part's node it started as (merge_parts_further), else -1
	// A union whose hull's reach (the certificate's costly half) is measured only once it comes first in
	// line to be merged: its hull and bridges until then, and its key in the memo.
	bool                              reach_open = false;
	std::shared_ptr<const ConvexHull> hull;
	std::vector<char>                 bridge;
	std::array<std::uint64_t, 3>      key{};
};

struct Candidate
{
	int   a = -1, b = -1;   // groups
	Group u;                 // their union
};

} // namespace

// The unions measured, by (first part, second part, cuts): the union as a group without its leaves, or
// none where it failed the certificate.
struct MergeMemo::Unions
{
	SharedResults<std::array<std::uint64_t, 3>, std::optional<Group>> by_key;
	SharedResults<std::array<std::uint64_t, 3>, HullReach>            reaches;   // of the unions by_key holds
	std::atomic<size_t>                                                candidates{0};
};

namespace {

class Merger
{
public:
	// `first`: none to start from the leaves and measure every pair; else the parts as they stand
	// are the groups and the first pairs measured are those `first` holds for.
	Merger(Decomposition& D, double tau, const std::function<bool(int, const char*)>& progress, double seconds,
	       MergeMemo* memo, MergeMeasure measure, const std::function<bool(int, int)>* first = nullptr)
	    : D(D), tau(tau), eps(1e-9 * extent(D.nodes[0].mesh.V)), measure(measure),
	      by_hull(measure == MergeMeasure::HullDistance), progress(progress), seconds(seconds),
	      start(std::chrono::steady_clock::now()), memo(memo), first(first), heap(Later{this})
	{
	}

	int run()
	{
		start_groups();
		start_neighbours();
		std::vector<std::pair<int, int>> pairs;
		for (int a = 0; a < (int) groups.size(); ++a)
			for (int b : nbr[a])
				if (a < b && (!first || (*first)(groups[a].origin, groups[b].origin))) pairs.push_back({a, b});
		score(pairs);
		greedy();
		record();
		return merges;
	}

private:
	Decomposition&                                  D;
	const double                                    tau, eps;
	const MergeMeasure                              measure;
	const bool                                      by_hull;   // measure is HullDistance: no notch need lie within tau
	const std::function<bool(int, const char*)>&    progress;
	const double                                    seconds;   // 0: no time limit
	const std::chrono::steady_clock::time_point     start;
	MergeMemo* const                                memo;
	const std::function<bool(int, int)>* const      first;
	std::vector<Group>                              groups;
	std::vector<std::set<int>>                      nbr;
	std::map<std::pair<int, int>, int>              contact;   // neighbouring leaves -> the cut between them
	std::map<std::string, int>                      by_path;
	std::vector<Candidate>                          pool;
	int                                             merges = 0;

	// The least concave union first. Concavities within rounding of each other (a symmetric solid's
	// congruent unions) tie, and ties go by the groups' first leaves' paths: a pose-free order.
	struct Later
	{
		const Merger* m;
		bool          operator()(int i, int j) const
		{
			const Candidate &x = m->pool[i], &y = m->pool[j];
			const long long  cx = std::llround(x.u.part.concavity / m->eps), cy = std::llround(y.u.part.concavity / m->eps);
			if (cx != cy) return cx > cy;
			return m->key(x) > m->key(y);
		}
	};
	std::priority_queue<int, std::vector<int>, Later> heap;

	std::pair<std::string, std::string> key(const Candidate& c) const
	{
		return {D.nodes[groups[c.a].leaves[0]].path, D.nodes[groups[c.b].leaves[0]].path};
	}

	void start_groups()
	{
		for (int k = 0; k < (int) D.nodes.size(); ++k) by_path[D.nodes[k].path] = k;
		for (int l : first ? D.parts() : D.leaves()) {
			const Node& n = D.nodes[l];
			Group       g;
			g.leaves  = n.merged.empty() ? std::vector<int>{l} : n.merged;
			g.origin  = first ? l : -1;
			g.part    = n;
			g.content = memo ? content_hash(n.mesh) : 0;
			if (!n.merged.empty()) face_components(n.mesh, &g.shells);
			// Only certified parts merge: an uncut leaf or one holding a kept cavity stays as it is.
			g.alive = n.cavities == 0 && certified(n, tau);
			groups.push_back(std::move(g));
		}
	}

	// The hull vertices and notches of the pairs' groups, where not yet found (a solid's hull has
	// vertices): only for groups some pair is measured with (merge_parts_further starts from a few).
	void find_extremes(const std::vector<std::pair<int, int>>& pairs)
	{
		std::vector<int> todo;
		for (const auto& [a, b] : pairs)
			for (int g : {a, b})
				if (groups[g].extreme.empty()) todo.push_back(g);
		std::sort(todo.begin(), todo.end());
		todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
		parallel_for(todo.size(), [&](size_t i) {
			Group& g  = groups[todo[i]];
			g.extreme = extreme_points(g.part.mesh.V);
			if (!by_hull) g.notches = notch_points(g.part.mesh, Topology(g.part.mesh));   // the notch prefilter's
		});
	}

	double bar() const { return reach_bar(tau); }   // the cuts' certificate's

	void start_neighbours()
	{
		nbr.assign(groups.size(), {});
		std::vector<int> index(D.nodes.size(), -1);
		for (int g = 0; g < (int) groups.size(); ++g)
			for (int l : groups[g].leaves) index[l] = g;
		for (const LeafContact& c : neighbouring_leaves(D)) {
			contact[{c.a, c.b}] = c.cut;
			const int ga = index[c.a], gb = index[c.b];
			if (!groups[ga].alive || !groups[gb].alive) continue;
			nbr[ga].insert(gb);
			nbr[gb].insert(ga);
		}
		if (by_hull) near_across_solids();
	}

	// The solid (shell) a leaf lies in: its path down to the child of its deepest ancestor split into
	// the input's solids (A | rest), or "" when the input is one solid.
	std::string solid_of(int leaf) const
	{
		const std::string& p = D.nodes[leaf].path;
		for (size_t n = p.size() - 1; n >= 1; --n) {
			const auto it = by_path.find(p.substr(0, n));
			if (it != by_path.end() && D.nodes[it->second].solids) return p.substr(0, n + 1);
		}
		return "";
	}

	// Parts of different solids of the input (an assembly's rod and its end pieces) share no cut, yet
	// one hull may stand for both within tau, as a peer's single hull does: under the hull-distance
	// certificate, parts of disjoint solids whose boxes come within twice the certificate's bar of each
	// other are neighbours too (farther apart, the middle of the gap between them, which their hull
	// spans, lies farther than the bar from both), and their union is the two solids side by side.
	void near_across_solids()
	{
		if (std::none_of(D.nodes.begin(), D.nodes.end(), [](const Node& n) { return n.solids; })) return;   // one solid
		std::vector<std::set<std::string>> solids(groups.size());
		std::vector<Eigen::AlignedBox3d>   box(groups.size());
		for (int g = 0; g < (int) groups.size(); ++g) {
			if (!groups[g].alive) continue;
			for (int l : groups[g].leaves) solids[g].insert(solid_of(l));
			box[g] = bounding_box(groups[g].part.mesh.V);
		}
		const double gap = 2 * bar();
		for (int a = 0; a < (int) groups.size(); ++a)
			for (int b = a + 1; b < (int) groups.size(); ++b) {
				if (!groups[a].alive || !groups[b].alive || solids[a].count("") || solids[b].count("")) continue;
				bool apart = true;
				for (const std::string& x : solids[a]) apart &= !solids[b].count(x);
				const bool near = ((box[a].min() - box[b].max()).array() <= gap).all() &&
				                  ((box[b].min() - box[a].max()).array() <= gap).all();
				if (!apart || !near) continue;
				nbr[a].insert(b);
				nbr[b].insert(a);
			}
	}

	// The cuts between the leaves: the nodes with some of them below each child.
	std::vector<Plane> separating(const std::vector<int>& leaves) const
	{
		std::map<std::string, int> sides;
		for (int l : leaves) {
			const std::string& p = D.nodes[l].path;
			for (size_t n = 1; n < p.size(); ++n) sides[p.substr(0, n)] |= p[n] == '0' ? 1 : 2;
		}
		std::vector<Plane> planes;
		for (const auto& [path, both] : sides) {
			const auto it = by_path.find(path);
			if (both == 3 && it != by_path.end() && D.nodes[it->second].has_plane) planes.push_back(D.nodes[it->second].plane);
		}
		return planes;
	}

	// A group's own crossings: a merged group's were counted when it was made, a leaf's only when a
	// union with it crosses itself (rarely), not for every leaf up front.
	static long own_crossings(const Group& g)
	{
		return g.crossings >= 0 ? g.crossings : (long) self_crossings(g.part.mesh, bbox_diagonal(g.part.mesh.V)).size();
	}

	// The cuts groups a and b touch along, where their faces are glued.
	std::vector<Plane> contact_planes(int a, int b) const
	{
		std::set<int> cuts;
		for (int x : groups[a].leaves)
			for (int y : groups[b].leaves) {
				const auto it = contact.find({std::min(x, y), std::max(x, y)});
				if (it != contact.end()) cuts.insert(it->second);
			}
		std::vector<Plane> planes;
		for (int c : cuts) planes.push_back(D.nodes[c].plane);
		return planes;
	}

	std::vector<int> merged_leaves(int a, int b) const
	{
		const Group &A = groups[a], &B = groups[b];
		std::vector<int> leaves;
		std::merge(A.leaves.begin(), A.leaves.end(), B.leaves.begin(), B.leaves.end(), std::back_inserter(leaves),
		           [&](int x, int y) { return D.nodes[x].path < D.nodes[y].path; });
		return leaves;
	}

	// The union of groups a and b if it passes the certificate; from the memo when it was measured.
	std::optional<Group> unite(int a, int b) const
	{
		const std::vector<Plane> planes = contact_planes(a, b);
		const std::vector<int>   leaves = merged_leaves(a, b);
		if (!memo) return measure_union(a, b, planes, leaves);
		const std::uint64_t                cuts[2] = {planes_hash(planes), planes_hash(separating(leaves))};
		const std::array<std::uint64_t, 3> key     = {groups[a].content, groups[b].content, mix(0, cuts, sizeof cuts)};
		// Measured, or being measured by the other search: the same union whichever leaves it took.
		std::optional<Group> g = memo->unions->by_key.find_or_make(key, [&] {
			std::optional<Group> made = measure_union(a, b, planes, leaves);
			if (made) ++memo->unions->candidates;
			return made;
		});
		if (g) g->leaves = leaves, g->key = key;
		return g;
	}

	// `planes`: the cuts they touch along (contact_planes); `leaves`: both groups' (merged_leaves). Its
	// reach is left open (measure_reach).
	std::optional<Group> measure_union(int a, int b, const std::vector<Plane>& planes, std::vector<int> leaves) const
	{
		const Group &A = groups[a], &B = groups[b];
		// Outside both parts the distance to their union is the distance to the nearer part, so the
		// union's hull reach is measured without the union: most pairs fail here, cheaply. The search
		// stops at the first point beyond the certificate's bar (no refining: relative 1e9), which the
		// union would fail whatever its measure finds, or after a bounded effort; the union's own
		// measure settles the rest.
		const Node &PA = A.part, &PB = B.part;
		TriMesh     both = PA.mesh;
		append(both, PB.mesh);
		std::vector<Vec3> corners = A.extreme;
		corners.insert(corners.end(), B.extreme.begin(), B.extreme.end());
		const ConvexHull h(corners);
		if (!by_hull && notch_deeper_than_tau(A, B, h, planes)) return std::nullopt;   // by the hull, notches may lie deeper
		if (hull_reach(both, h, std::vector<char>(h.facets(), 1), bar(), 0.1 * tau, 1e9, kReachPrefilter).lower > bar())
			return std::nullopt;
		Solid s;
		try {   // crossings searched last: most unions fail before, and the search costs as much as a measure
			s = make_solid(planes.empty() ? both : glue(PA.mesh, PB.mesh, planes, eps), false);
		}
		catch (const std::exception&) {   // the glued surface is not a clean solid (a seam left open)
			return std::nullopt;
		}
		// Glued along a cut, at least two of their shells become one; side by side, none does.
		const int shells = A.shells + B.shells - (planes.empty() ? 0 : 1);
		if (s.shells < 1 || s.shells > shells || (planes.empty() && s.shells != shells) || s.cavities > 0)
			return std::nullopt;
		if (std::abs(s.volume - PA.volume - PB.volume) > 1e-6 * (PA.volume + PB.volume)) return std::nullopt;
		const Topology        topo(s.mesh);
		auto                  hull = std::make_shared<const ConvexHull>(s.mesh.V);
		const ConcavityReport rep  = measure_concavity(s.mesh, topo, *hull, tau, Reach::Left);
		Group                 g;
		Node&                 n = g.part;
		n.concavity           = rep.max_concavity;
		n.volume              = s.volume;
		n.notch_count         = rep.notches;
		if (rep.max_vertex >= 0) n.notch = s.mesh.V[rep.max_vertex];
		if (!by_hull && n.concavity > tau) return std::nullopt;   // the concavity certificate's notch half
		g.reach_open = true;
		g.hull       = std::move(hull);
		g.bridge     = rep.bridge;
		g.shells  = s.shells;
		n.mesh    = std::move(s.mesh);
		g.extreme = extreme_points(corners);
		g.leaves  = std::move(leaves);
		return g;   // its folds are counted if it comes to be merged (settle)
	}

	// A union about to be merged, if it has no fold of its own: it crosses itself no more than groups a
	// and b did (a part cut from a surface that nearly touches itself may carry such crossings from the
	// cuts). Counted for the unions merged only, not for every union that passes the certificate: the
	// crossing search costs about as much as the union's measure. What later unions need of it too.
	bool settle(Group& u, int a, int b) const
	{
		Solid s;
		std::swap(s.mesh, u.part.mesh);
		find_crossings(s);
		const long crossings = crossings_off_cuts(s, separating(u.leaves), eps);
		std::swap(s.mesh, u.part.mesh);
		if (crossings > 0 && crossings > own_crossings(groups[a]) + own_crossings(groups[b])) return false;
		u.crossings = crossings;
		if (!by_hull) u.notches = notch_points(u.part.mesh, Topology(u.part.mesh));
		u.content   = memo ? content_hash(u.part.mesh) : 0;
		return true;
	}

	// A lower bound of the union's concavity from its parts' notches: a notch away from the cuts they
	// are glued along keeps its faces in the union, and its concavity there (its distance to a bridge
	// of the union's hull) is at least its distance to that hull's boundary. True once one lies deeper
	// than tau (and the hull's rounding: the union's own hull is built from its own vertices).
	bool notch_deeper_than_tau(const Group& A, const Group& B, const ConvexHull& h, const std::vector<Plane>& planes) const
	{
		const double size = extent(h.points), seam = 1e-6 * size, deep = tau + 1e-6 * size;
		int          hint = -1;   // a hull triangle
		for (const Group* G : {&A, &B})
			for (const Vec3& x : G->notches) {
				bool off = true;
				for (const Plane& pl : planes) off &= std::abs(pl.eval(x)) > seam;
				if (!off) continue;
				// Inside the hull the distance to its boundary is the least distance to a facet's
				// plane: the facet that held the last notch (notches lie along the surface, near each
				// other) often settles it, else the hull's own distance tree does.
				if (hint >= 0 && -h.facet_plane[h.triangle_facet[hint]].eval(x) <= deep) continue;
				if (h.distance_to_boundary(x, &hint, hint) > deep) return true;
			}
		return false;
	}

	// True once the time limit has passed: merging stops there (what is merged stays merged).
	bool out_of_time()
	{
		if (seconds > 0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds)
			D.merge_time_limit_reached = true;
		return D.merge_time_limit_reached;
	}

	void report(const char* msg) const
	{
		if (progress && !progress(99, msg)) throw Error(Error::Cancelled, "The decomposition was cancelled.");
	}

	// Unite the pairs on all cores and queue those that pass. The largest unions are started first and
	// no batch waits for its slowest, so no core idles while another measures a large union; progress
	// and the time limit are heard on the calling thread between its pairs.
	void score(const std::vector<std::pair<int, int>>& pairs)
	{
		find_extremes(pairs);
		const auto faces = [&](size_t i) { return groups[pairs[i].first].part.mesh.F.size() + groups[pairs[i].second].part.mesh.F.size(); };
		std::vector<size_t> order(pairs.size());
		for (size_t i = 0; i < order.size(); ++i) order[i] = i;
		std::stable_sort(order.begin(), order.end(), [&](size_t i, size_t j) { return faces(i) > faces(j); });
		std::vector<std::optional<Group>> u(pairs.size());
		std::atomic<size_t>               measured{0};
		std::atomic<bool>                 stop{out_of_time()};
		const std::thread::id             caller = std::this_thread::get_id();
		parallel_for(order.size(), [&](size_t k) {
			if (stop) return;
			u[order[k]]    = unite(pairs[order[k]].first, pairs[order[k]].second);
			const size_t n = ++measured;
			if (std::this_thread::get_id() != caller) return;
			try {
				if (out_of_time()) stop = true;
				if (pairs.size() > 4 * available_threads()) {
					char msg[96];
					std::snprintf(msg, sizeof msg, "Merging neighbouring parts: %zu of %zu pairs measured", n, pairs.size());
					report(msg);
				}
			}
			catch (...) {
				stop = true;
				throw;
			}
		});
		for (size_t i = 0; i < pairs.size(); ++i) {
			if (!u[i]) continue;
			pool.push_back({pairs[i].first, pairs[i].second, std::move(*u[i])});
			heap.push((int) pool.size() - 1);
		}
	}

	// Union u's hull reach, as the cuts' measure refines it and charges it (measure_concavity with
	// Reach::Always; shared through the memo by the two searches): its hull distance, and beyond tau its
	// concavity, which fails the certificate.
	void measure_reach(Group& u) const
	{
		const auto      make = [&] { return bridges_reach(u.part.mesh, *u.hull, u.bridge, tau); };
		const HullReach hr   = memo ? memo->unions->reaches.find_or_make(u.key, make) : make();
		Node&           n    = u.part;
		n.hull_distance       = hr.lower;
		n.hull_distance_bound = hr.upper;
		n.concavity           = std::max(n.concavity, reach_charge(hr, *u.hull, tau));
		u.reach_open = false;
		u.hull.reset();
		u.bridge = std::vector<char>();
	}

	// The reach of the first unions in line, one per core, when the first has none yet. Most unions never
	// come first (a neighbour of theirs merges before), so most reaches are never measured; the line is
	// the heap's, so the merges are those of measuring every union as it is scored.
	void measure_reach_in_line()
	{
		std::vector<int> line;
		while (!heap.empty() && line.size() < available_threads()) {
			const int i = heap.top();
			if (!groups[pool[i].a].alive || !groups[pool[i].b].alive) {   // skipped when popped anyway
				heap.pop();
				pool[i].u = Group();
				continue;
			}
			if (!pool[i].u.reach_open) break;
			heap.pop();   // its concavity may change: out of the heap while measured
			line.push_back(i);
		}
		parallel_for(line.size(), [&](size_t k) { measure_reach(pool[line[k]].u); });
		for (int i : line) heap.push(i);
	}

	void greedy()
	{
		while (!heap.empty() && !out_of_time()) {
			measure_reach_in_line();
			if (heap.empty() || pool[heap.top()].u.reach_open) continue;   // one measured over tau sank in line
			const int i = heap.top();
			heap.pop();
			const int a = pool[i].a, b = pool[i].b;
			Group u = std::move(pool[i].u);
			pool[i].u = Group();
			if (!groups[a].alive || !groups[b].alive) continue;   // one of them has merged since
			if (!certify_merged(u.part, tau, measure) || !settle(u, a, b)) continue;
			for (int x : {a, b}) {   // merged away: only its leaves are kept
				groups[x].alive = false;
				groups[x].part  = Node();
				groups[x].extreme.clear();
			}
			const int g = (int) groups.size();
			groups.push_back(std::move(u));
			std::set<int> around;
			for (int x : {a, b})
				for (int n : nbr[x])
					if (n != a && n != b) around.insert(n);
			nbr.push_back(around);
			std::vector<std::pair<int, int>> pairs;
			for (int n : around) {
				nbr[n].erase(a), nbr[n].erase(b), nbr[n].insert(g);
				pairs.push_back({n, g});
			}
			++merges;
			char msg[96];
			std::snprintf(msg, sizeof msg, "Merging neighbouring parts: %d merged", merges);
			report(msg);
			score(pairs);
		}
	}

	// Each merged part becomes a node after the tree's, its leaves pointing to it. A merged part the
	// merge started from and united further is dropped.
	void record()
	{
		std::vector<char> drop(D.nodes.size(), 0);
		for (Group& g : groups) {
			if (g.origin >= 0 && !g.alive && !D.nodes[g.origin].merged.empty()) drop[g.origin] = 1;
			if (!g.alive || g.leaves.size() < 2 || g.origin >= 0) continue;
			Node& n      = g.part;
			n.path       = D.nodes[g.leaves[0]].path + "+" + std::to_string(g.leaves.size() - 1);
			n.merged     = g.leaves;
			const int id = (int) D.nodes.size();
			for (int l : g.leaves) D.nodes[l].part = id;
			D.nodes.push_back(std::move(n));
			drop.push_back(0);
		}
		drop_nodes(D, drop);
		D.merges = first ? D.merges + merges : merges;
	}
};

} // namespace

MergeMemo::MergeMemo() : unions(std::make_unique<Unions>()) {}
MergeMemo::~MergeMemo() = default;
size_t MergeMemo::size() const
{
	return unions->by_key.size();
}
size_t MergeMemo::candidates() const
{
	return unions->candidates;
}
size_t MergeMemo::reaches() const
{
	return unions->reaches.size();
}

namespace {

// The leaves on either side of cut node `c` whose caps on its plane overlap.
std::vector<LeafContact> contacts_across(const Decomposition& D, int c, double eps)
{
	const Node&                    n = D.nodes[c];
	const Vec3                     u = n.plane.n.unitOrthogonal(), w = n.plane.n.cross(u);
	std::vector<int>               side[2];
	std::vector<std::vector<Tri2>> caps[2];
	for (int s = 0; s < 2; ++s)
		for (int l : leaves_below(D, n.child[s])) {
			std::vector<Tri2> cap = cap_on(D.nodes[l].mesh, n.plane, u, w, eps);
			if (cap.empty()) continue;
			side[s].push_back(l);
			caps[s].push_back(std::move(cap));
		}
	std::vector<LeafContact> out;
	for (size_t i = 0; i < side[0].size(); ++i)
		for (size_t j = 0; j < side[1].size(); ++j)
			if (caps_overlap(caps[0][i], caps[1][j], eps))
				out.push_back({std::min(side[0][i], side[1][j]), std::max(side[0][i], side[1][j]), c});
	return out;
}

} // namespace

// Each cut's contacts on its own core (the cuts near the root, with the most leaves below, first),
// gathered in node order.
std::vector<LeafContact> neighbouring_leaves(const Decomposition& D)
{
	const double     eps = 1e-9 * extent(D.nodes[0].mesh.V);
	std::vector<int> cuts;
	for (int k = 0; k < (int) D.nodes.size(); ++k)
		if (D.nodes[k].has_plane && !D.nodes[k].solids) cuts.push_back(k);
	std::vector<std::vector<LeafContact>> found(cuts.size());
	parallel_for(cuts.size(), [&](size_t i) { found[i] = contacts_across(D, cuts[i], eps); });
	std::vector<LeafContact> out;
	for (const auto& f : found) out.insert(out.end(), f.begin(), f.end());
	return out;
}

int merge_parts(Decomposition& D, double tau, const std::function<bool(int, const char*)>& progress, double seconds,
                MergeMemo* memo, MergeMeasure measure)
{
	return Merger(D, tau, progress, seconds, memo, measure).run();
}

int merge_parts_further(Decomposition& D, double tau, const std::function<bool(int, int)>& first,
                        const std::function<bool(int, const char*)>& progress, double seconds, MergeMemo* memo,
                        MergeMeasure measure)
{
	return Merger(D, tau, progress, seconds, memo, measure, &first).run();
}

void drop_nodes(Decomposition& D, const std::vector<char>& drop)
{
	std::vector<int> id(D.nodes.size(), -1);
	int              kept = 0;
	for (size_t k = 0; k < D.nodes.size(); ++k)
		if (!drop[k]) id[k] = kept++;
	if (kept == (int) D.nodes.size()) return;
	std::vector<Node> nodes;
	nodes.reserve(kept);
	for (size_t k = 0; k < D.nodes.size(); ++k) {
		if (drop[k]) continue;
		renumber(D.nodes[k], id);
		nodes.push_back(std::move(D.nodes[k]));
	}
	D.nodes = std::move(nodes);
}

} // namespace acd
