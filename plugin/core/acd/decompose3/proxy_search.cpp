// The search on a proxy (proxy_search.h): decimate, cut the proxy, replay its cuts on the solid, certify
// every part on the solid, search the parts that fail again on a finer proxy or as they are.
#include "acd/decompose3/proxy_search.h"
#include "acd/decompose3/measure_memo.h"
#include "acd/decompose3/merge.h"
#include "acd/mesh/decimate.h"
#include "acd/mesh/measures.h"
#include "acd/mesh/nearest.h"
#include "acd/mesh/parallel.h"
#include "acd/solid/glue.h"
#include "acd/solid/separate.h"
#include "acd/solid/solid.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <thread>

namespace acd {

namespace {

constexpr size_t kDistanceSamples = 200000;   // the solid's vertices the proxy's distance is measured at

// How far the solid's surface lies from the proxy's: the largest distance from the solid's vertices
// (every one, or evenly spaced ones on a big solid) to the proxy.
double distance_to(const TriMesh& proxy, const TriMesh& solid)
{
	return NearestOnSurface(proxy).farthest(solid.V, kDistanceSamples);
}

struct Proxy
{
	Solid  solid;
	double distance = 0;
};

// The solid decimated to about `faces`, if that is a clean solid (closed, no crossing) within `widest`
// of it and clearly coarser than it. (A solid that crosses itself is searched as it is: cuts through a
// decimated crossing open parts far more often than through the crossing itself.)
std::optional<Proxy> make_proxy(const TriMesh& mesh, int faces, double error, double widest)
{
	Decimated d = decimate(mesh, faces, error);
	if (2 * d.mesh.F.size() > mesh.F.size()) return std::nullopt;
	Proxy p;
	try {
		p.solid = make_solid(d.mesh);
	}
	catch (const Error&) {
		return std::nullopt;
	}
	if (p.solid.self_intersections > 0) return std::nullopt;
	p.distance = distance_to(p.solid.mesh, mesh);
	if (!(p.distance <= widest)) return std::nullopt;
	return p;
}

// The solids of `mesh` split as a proxy's node split its own: the solid nearest to the proxy's first
// child (by centroid) first, the rest second.
bool split_solids(const TriMesh& mesh, const TriMesh& first, std::array<TriMesh, 2>& parts)
{
	std::vector<TriMesh> solids = connected_solids(mesh);
	if (solids.size() < 2) return false;
	const auto centroid = [](const TriMesh& m) {
		Vec3 c = Vec3::Zero();
		for (const Vec3& p : m.V) c += p;
		return Vec3(c / (double) std::max<size_t>(1, m.V.size()));
	};
	const Vec3 target = centroid(first);
	size_t     pick   = 0;
	for (size_t k = 1; k < solids.size(); ++k)
		if ((centroid(solids[k]) - target).norm() < (centroid(solids[pick]) - target).norm()) pick = k;
	parts = {std::move(solids[pick]), TriMesh()};
	for (size_t k = 0; k < solids.size(); ++k)
		if (k != pick) append(parts[1], solids[k]);
	return true;
}

class ProxySearch
{
public:
	ProxySearch(const DecomposeOptions& o, const ProxySettings& ps, MergeMemo* memo, MeasureMemo* measures)
	    : o(o), ps(ps), memo(memo), measures(measures), keep(o.hole_handling == HoleHandling::KeepCavities),
	      start(std::chrono::steady_clock::now())
	{
	}

	// A small solid (or one with a max_parts bound) searched as it is; a large one on a proxy, replayed
	// and certified on the solid from the root down.
	Decomposition run(const Solid& solid)
	{
		if (o.max_parts > 0 || (int) solid.mesh.F.size() <= ps.above) return cut_and_merge(solid, o.merge_parts, o);
		D.tau = o.tau;
		eps   = 1e-9 * extent(solid.mesh.V);
		Node root;
		root.path = "0";
		root.mesh = solid.mesh;
		D.nodes.push_back(std::move(root));
		search_node(0, 0, o.merge_parts);
		if (o.merge_parts && !retried.empty()) merge_across();
		raise_to_children();
		return D;
	}

private:
	const DecomposeOptions&                     o;
	const ProxySettings&                        ps;
	MergeMemo* const                            memo;       // unions an earlier search measured (or none)
	MeasureMemo* const                          measures;   // and parts (or none)
	const bool                                  keep;
	const std::chrono::steady_clock::time_point start;
	Decomposition                               D;
	std::vector<std::string>                    retried;   // the paths of the leaves searched again
	std::set<std::string>                       as_is;     // those of them searched as they are
	double                                      eps = 0;   // the width of a cut plane on the solid

	// An inner node's concavity is the copy's widened by its distance: an estimate, which a child
	// measured on the solid can pass. Raised to its children's, a node never needs less than its parts
	// (the level of detail reads the tree so, coarse to fine).
	void raise_to_children()
	{
		std::vector<int> order{0};   // preorder: a parent before its children
		for (size_t i = 0; i < order.size(); ++i)
			for (int c : D.nodes[order[i]].child)
				if (c >= 0) order.push_back(c);
		for (size_t i = order.size(); i-- > 0;)
			for (int c : D.nodes[order[i]].child)
				if (c >= 0) D.nodes[order[i]].concavity = std::max(D.nodes[order[i]].concavity, D.nodes[c].concavity);
	}

	// The time limit's rest (0: none).
	double left() const
	{
		if (!(o.time_limit_seconds > 0)) return 0;
		return std::max(o.time_limit_seconds - std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1e-9);
	}

	bool needs_search(const Node& n) const { return !certified(n, o.tau) || (!keep && n.cavities > 0); }

	// The stages after the proxy's search take time on a large mesh: say which, and hear a cancel.
	void report(const char* msg) const
	{
		if (o.progress && !o.progress(99, msg)) throw Error(Error::Cancelled, "The decomposition was cancelled.");
	}

	// Leaf `at` searched on the coarsest proxy from `level` on that is clean and near enough, else as it
	// is: the proxy cut (and merged), its cuts replayed on the solid, its merged parts united on the
	// solid, every part certified on the solid, and the parts that fail searched again.
	void search_node(int at, int level, bool merge)
	{
		std::optional<Proxy> px;
		for (; level < ps.levels && !px; ++level) {
			const int faces = proxy_faces(at, level);
			if (faces == 0) break;
			report("Simplifying the mesh for the search");
			px = make_proxy(D.nodes[at].mesh, faces, ps.error * o.tau, ps.widest * o.tau);
		}
		if (!px) return search_as_is(at, merge);
		if (D.proxy_searches++ == 0) D.proxy_faces = (int) px->solid.mesh.F.size(), D.proxy_distance = px->distance;
		std::optional<Decomposition> found = proxy_tree(*px, merge);
		if (!found) return search_as_is(at, merge);
		Decomposition& P = *found;
		if (D.proxy_searches == 1) D.pick_rule = P.pick_rule;   // the rule of the solid's own search
		absorb(P);
		D.merges -= P.merges;   // the proxy's merges count as certify makes them on the solid
		std::vector<int>   leaves;
		std::map<int, int> reached;   // the proxy's leaves the replay reached: their nodes in D
		report("Cutting the mesh by the planes found on its simplified copy");
		replay(at, P, px->distance, leaves, reached);
		report("Certifying every part on the mesh itself");
		std::map<int, MeasuredPtr> failed = certify(P, reached, leaves);
		std::vector<int>           again;
		for (int l : leaves)
			if (failed.count(l)) again.push_back(l);
		if (!D.time_limit_reached) search_again(again, failed, level, merge);
	}

	// The proxy's cut tree (and merge): under cut_search=thorough one per pick rule, the better kept, as
	// decompose() does on a small solid (the proxy makes the second search cheap, and only the tree
	// kept is replayed and certified on the solid). None if a cut opened a proxy's part (a fold
	// decimation made): the solid is then searched as it is.
	std::optional<Decomposition> proxy_tree(const Proxy& px, bool merge) const
	{
		DecomposeOptions po = o;
		po.tau              = std::max(o.tau - px.distance, 0.5 * o.tau);   // so that the solid's parts rarely fail where the proxy's pass
		const bool  both    = o.cut_search == CutSearch::Thorough;
		MergeMemo   unions;     // the trees share their first cuts, and their merges many unions
		MeasureMemo parts;      // and the parts their planes make at the nodes they share
		std::optional<Decomposition> kept;
		for (PickRule rule : {PickRule::WorseHalf, PickRule::PartsNeeded}) {
			if (rule == PickRule::PartsNeeded && (!both || (kept && kept->time_limit_reached))) break;
			po.pick_rule          = rule;
			po.time_limit_seconds = left();
			if (both && o.progress) {
				const int from = rule == PickRule::WorseHalf ? 0 : 50;
				po.progress    = [&, from](int pct, const char* msg) { return o.progress(from + pct / 2, msg); };
			}
			Decomposition P;
			try {
				P = cut_tree(px.solid, po, nullptr, both ? &parts : nullptr);
			}
			catch (const Error& e) {
				if (e.code != Error::OpenPart) throw;
				return std::nullopt;
			}
			if (merge) merge_parts(P, o.tau, po.progress, left(), both ? &unions : memo, o.merge_measure);
			P.pick_rule = rule;
			if (!kept || better_plan(P, *kept, o.tau)) kept = std::move(P);
		}
		return kept;
	}

	// True if leaf `at` is searched as it is from proxy level `level` on (search_node's first test).
	bool as_is_from(int at, int level) const { return proxy_faces(at, level) == 0; }

	// The faces of leaf `at`'s proxy at `level`, 0 where it is searched as it is: above ps.above, the
	// first proxy has ps.faces but at most half the leaf's, each finer one four times as many while
	// that is under half the leaf's.
	int proxy_faces(int at, int level) const
	{
		const int n = (int) D.nodes[at].mesh.F.size();
		if (level >= ps.levels || n <= ps.above) return 0;
		const int faces = ps.faces << (2 * level);
		if (level == 0) return std::min(faces, n / 2);
		return 2 * faces < n ? faces : 0;
	}

	// The leaves that failed, searched again in leaf order. Those searched as they are go all at once
	// (largest first), their trees grafted in leaf order after; the rest in turn. The reports go
	// through the calling thread, and a cancel there reaches the other searches at their next report.
	void search_again(const std::vector<int>& again, const std::map<int, MeasuredPtr>& measured, int level, bool merge)
	{
		std::vector<int> now;
		for (int l : again)
			if (as_is_from(l, level)) now.push_back(l);
		std::stable_sort(now.begin(), now.end(), [&](int a, int b) { return D.nodes[a].mesh.F.size() > D.nodes[b].mesh.F.size(); });
		std::vector<Decomposition> found(now.size());
		std::map<int, size_t>      at;   // leaf -> its search in `found`
		for (size_t i = 0; i < now.size(); ++i) at[now[i]] = i;
		std::atomic<bool>     cancelled{false};
		const std::thread::id caller = std::this_thread::get_id();
		DecomposeOptions      eo     = o;
		eo.progress                  = [&](int pct, const char* msg) {
            if (std::this_thread::get_id() == caller && o.progress && !o.progress(pct, msg)) cancelled = true;
            return !cancelled.load();
		};
		parallel_for(now.size(), [&](size_t i) { found[i] = cut_and_merge(solid_of(now[i]), merge, eo, measured.at(now[i])); });
		for (int l : again) {
			if (!at.count(l) && D.time_limit_reached) continue;
			++D.proxy_retries;
			retried.push_back(D.nodes[l].path);
			if (!at.count(l)) {
				search_node(l, level, merge);
				continue;
			}
			as_is.insert(D.nodes[l].path);
			absorb(found[at[l]]);
			graft(l, found[at[l]]);
		}
	}

	// A leaf searched again was merged within its own search only: its parts and their neighbours
	// are merged across now, the pairs with a part below such a leaf measured first. Two parts of one
	// leaf searched as it is were measured together by that search's merge on the mesh itself (and
	// stayed apart): they are not measured again.
	void merge_across()
	{
		report("Merging the parts searched again with their neighbours");
		const auto within = [&](int p) {   // the deepest leaf searched again that p lies below, or none
			const std::string& path = D.nodes[p].path;
			const std::string* in   = nullptr;
			for (const std::string& r : retried)
				if (path.rfind(r, 0) == 0 && (!in || r.size() > in->size())) in = &r;
			return in;
		};
		const std::function<bool(int, int)> across = [&](int a, int b) {
			const std::string *ra = within(a), *rb = within(b);
			if (!ra && !rb) return false;
			return !(ra && rb && *ra == *rb && as_is.count(*ra));
		};
		merge_parts_further(D, o.tau, across, o.progress, left(), memo, o.merge_measure);
	}

	// Every leaf of the solid certified, or united with others as the proxy's merged parts unite them:
	// each such union that passes the certificate becomes a merged part, and the leaves of a union
	// refused are measured by the same task. The unions and the other leaves are measured on all cores
	// at once, the largest first, so that no core waits for one large union. The leaves that fail, with
	// their measure (a part's search starts from it).
	std::map<int, MeasuredPtr> certify(const Decomposition& P, const std::map<int, int>& reached, const std::vector<int>& leaves)
	{
		const std::vector<std::vector<int>> groups = proxy_groups(P, reached);
		std::vector<char>                   grouped(D.nodes.size(), 0);
		for (const std::vector<int>& g : groups)
			for (int l : g) grouped[l] = 1;
		// Tasks: group k as -1 - k, a leaf outside every group as its id; by faces, the largest first.
		std::vector<std::pair<size_t, int>> tasks;
		for (size_t k = 0; k < groups.size(); ++k) {
			size_t faces = 0;
			for (int l : groups[k]) faces += D.nodes[l].mesh.F.size();
			tasks.push_back({faces, -1 - (int) k});
		}
		for (int l : leaves)
			if (!grouped[l]) tasks.push_back({D.nodes[l].mesh.F.size(), l});
		std::stable_sort(tasks.begin(), tasks.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
		std::vector<std::vector<Node>> unions(groups.size());
		std::vector<MeasuredPtr>       measured(D.nodes.size());
		parallel_for(tasks.size(), [&](size_t i) {
			const int t = tasks[i].second;
			if (t >= 0) {
				measured[t] = measure_leaf(t);
				return;
			}
			const std::vector<int>& g = groups[-1 - t];
			unions[-1 - t]            = united_pieces(g);
			std::set<int> took;
			for (const Node& n : unions[-1 - t]) took.insert(n.merged.begin(), n.merged.end());
			for (int l : g)
				if (!took.count(l)) measured[l] = measure_leaf(l);
		});
		for (std::vector<Node>& pieces : unions)
			for (Node& n : pieces) {
				const int id = (int) D.nodes.size();
				for (int l : n.merged) D.nodes[l].part = id;
				D.merges += (int) n.merged.size() - 1;
				D.nodes.push_back(std::move(n));
			}
		std::map<int, MeasuredPtr> failed;
		for (int l : leaves)
			if (measured[l]) failed[l] = std::move(measured[l]);
		return failed;
	}

	// Leaf l measured on the solid and stopped by its hull as the cuts would stop it; its measure if it
	// fails the certificate, else none.
	MeasuredPtr measure_leaf(int l)
	{
		Node&       n  = D.nodes[l];
		MeasuredPtr ms = measure_node(n, keep, o.tau);
		stop_by_hull(n, *ms, o);
		return needs_search(n) ? ms : nullptr;
	}

	// The proxy's merged parts as groups of the solid's leaves: those whose leaves the replay all reached.
	static std::vector<std::vector<int>> proxy_groups(const Decomposition& P, const std::map<int, int>& reached)
	{
		std::vector<std::vector<int>> groups;
		for (int p : P.parts()) {
			std::vector<int> g;
			for (int l : P.nodes[p].merged)
				if (reached.count(l)) g.push_back(reached.at(l));
			if (g.size() > 1 && g.size() == P.nodes[p].merged.size()) groups.push_back(std::move(g));
		}
		return groups;
	}

	// A proxy's merged part on the solid: its leaves united whole if that passes, else in pieces, two
	// pieces at a time (in path order) while their union passes; the merged parts made. A union refused
	// once is not tried again after another grows, nor one of pieces that do not touch (two shells).
	std::vector<Node> united_pieces(const std::vector<int>& leaves) const
	{
		if (std::optional<Node> whole = united(leaves)) return {std::move(*whole)};
		std::vector<std::vector<int>>    pieces;
		std::vector<std::optional<Node>> made;
		std::set<std::vector<int>>       refused;
		for (int l : leaves) pieces.push_back({l}), made.emplace_back();
		for (bool grown = leaves.size() > 2; grown;) {
			grown = false;
			for (size_t i = 0; i < pieces.size() && !grown; ++i)
				for (size_t j = i + 1; j < pieces.size() && !grown; ++j) {
					if (pieces[i].size() + pieces[j].size() == leaves.size()) continue;   // the whole, refused
					std::vector<int> both;
					std::merge(pieces[i].begin(), pieces[i].end(), pieces[j].begin(), pieces[j].end(), std::back_inserter(both),
					           [&](int a, int b) { return D.nodes[a].path < D.nodes[b].path; });
					if (refused.count(both) || !touch(pieces[i], pieces[j])) continue;
					std::optional<Node> n = united(both);
					if (!n) refused.insert(std::move(both));
					else {
						pieces[i] = std::move(both), made[i] = std::move(n);
						pieces.erase(pieces.begin() + j), made.erase(made.begin() + j);
						grown = true;
					}
				}
		}
		std::vector<Node> out;
		for (std::optional<Node>& n : made)
			if (n) out.push_back(std::move(*n));
		return out;
	}

	// Whether some leaf of `a` and some leaf of `b` both reach the cut between them. Glue joins leaves
	// only across that cut, so pieces that do not touch stay two shells.
	bool touch(const std::vector<int>& a, const std::vector<int>& b) const
	{
		const auto reaches = [&](int leaf, const Plane& pl) {
            const std::vector<Vec3>& V = D.nodes[leaf].mesh.V;
            return std::any_of(V.begin(), V.end(), [&](const Vec3& p) { return std::abs(pl.eval(p)) <= eps; });
		};
		for (int x : a)
			for (int y : b) {
				const Node& c = D.nodes[between(x, y)];
				if (c.has_plane && reaches(x, c.plane) && reaches(y, c.plane)) return true;
			}
		return false;
	}

	// The cut between two leaves: their deepest common node.
	int between(int a, int b) const
	{
		const std::string &pa = D.nodes[a].path, &pb = D.nodes[b].path;
		size_t             n  = 0;
		while (n < pa.size() && n < pb.size() && pa[n] == pb[n]) ++n;
		int id = a;
		while (D.nodes[id].path.size() > n) id = D.nodes[id].parent;
		return id;
	}

	// The leaves (path order) glued into one solid, measured; if it is one certified solid without a
	// cavity holding their volume, as a merged part's node.
	std::optional<Node> united(const std::vector<int>& leaves) const
	{
		TriMesh      u   = D.nodes[leaves[0]].mesh;
		double       volume = D.nodes[leaves[0]].volume;
		std::vector<Plane> cuts;   // every cut between the leaves
		const auto         add = [](std::vector<Plane>& to, const Plane& pl) {
            if (std::none_of(to.begin(), to.end(), [&](const Plane& p) { return p.n == pl.n && p.d == pl.d; })) to.push_back(pl);
		};
		for (size_t k = 1; k < leaves.size(); ++k) {
			std::vector<Plane> planes;
			for (size_t j = 0; j < k; ++j) {
				const Node& c = D.nodes[between(leaves[j], leaves[k])];
				if (c.has_plane) add(planes, c.plane), add(cuts, c.plane);
			}
			u = glue(u, D.nodes[leaves[k]].mesh, planes, eps);
			volume += D.nodes[leaves[k]].volume;
		}
		Node  n;
		Solid s;
		try {   // crossings searched last, as in the merge
			s = make_solid(u, false);
			if (s.shells != 1 || s.cavities > 0 || std::abs(s.volume - volume) > 1e-6 * volume) return std::nullopt;
			n.mesh = s.mesh;
		}
		catch (const Error&) {
			return std::nullopt;
		}
		measure_node(n, keep, o.tau, o.merge_measure == MergeMeasure::HullDistance);
		if (!certify_merged(n, o.tau, o.merge_measure) || n.cavities > 0) return std::nullopt;
		// No fold of its own, as in the merge: crossings where leaves touch across a cut are none,
		// and the rest no more than the leaves carried from the cuts.
		find_crossings(s);
		if (const long crossings = crossings_off_cuts(s, cuts, eps); crossings > 0) {
			long own = 0;
			for (int l : leaves) own += (long) self_crossings(D.nodes[l].mesh, bbox_diagonal(D.nodes[l].mesh.V)).size();
			if (crossings > own) return std::nullopt;
		}
		n.path   = D.nodes[leaves[0]].path + "+" + std::to_string(leaves.size() - 1);
		n.merged = leaves;
		return n;
	}

	void search_as_is(int at, bool merge)
	{
		as_is.insert(D.nodes[at].path);
		Decomposition sub = cut_and_merge(solid_of(at), merge, o);
		absorb(sub);
		graft(at, sub);
	}

	// Node `at`'s mesh as a solid (a part of the input solid: closed and oriented as it was).
	Solid solid_of(int at) const
	{
		Solid s;
		s.mesh   = D.nodes[at].mesh;
		s.volume = signed_volume(s.mesh);
		face_components(s.mesh, &s.shells);
		return s;
	}

	// The search on `s` itself (and its merge), within the time left: the merge gets what the cuts left.
	// `with`: the options, but for their time limit; `root`: s measured already, or none.
	Decomposition cut_and_merge(const Solid& s, bool merge, const DecomposeOptions& with, MeasuredPtr root = nullptr) const
	{
		DecomposeOptions eo   = with;
		eo.time_limit_seconds = left();
		Decomposition sub     = cut_tree(s, eo, std::move(root), measures);
		if (merge) merge_parts(sub, o.tau, with.progress, left(), memo, o.merge_measure);
		return sub;
	}

	// A search's limits and counts into the tree.
	void absorb(const Decomposition& sub)
	{
		D.max_parts_reached |= sub.max_parts_reached;
		D.time_limit_reached |= sub.time_limit_reached;
		D.hole_cuts += sub.hole_cuts;
		D.kept_cavities += sub.kept_cavities;
		D.films_dropped += sub.films_dropped;
		D.film_volume += sub.film_volume;
		D.merges += sub.merges;
		D.merge_time_limit_reached |= sub.merge_time_limit_reached;
	}

	// The proxy's cut tree made on a mesh: the proxy node it follows, and its two parts if the node's
	// split splits the mesh as well.
	struct Replayed
	{
		int                                      pid = 0;
		TriMesh                                  mesh;
		std::array<std::unique_ptr<Replayed>, 2> child;
	};

	// The splits below `r`, the two sides of each on two cores (each split depends on its parent's alone).
	static void split_down(Replayed& r, const Decomposition& P)
	{
		const Node&            pn = P.nodes[r.pid];
		std::array<TriMesh, 2> parts;
		if (pn.child[0] < 0 || !split_like(r.mesh, P, pn, parts)) return;
		for (int s = 0; s < 2; ++s) {
			r.child[s]       = std::make_unique<Replayed>();
			r.child[s]->pid  = pn.child[s];
			r.child[s]->mesh = std::move(parts[s]);
		}
		parallel_for(2, [&](size_t s) { split_down(*r.child[s], P); });
	}

	// The proxy's cut tree on the solid from leaf `at` down: each of its cuts made by its plane on the
	// solid's node, as far as the plane splits it in two; the solid's leaves into `leaves`. Inner nodes
	// keep the proxy's measures widened by its distance; the leaves are measured on the solid later.
	void replay(int at, const Decomposition& P, double e, std::vector<int>& leaves, std::map<int, int>& reached)
	{
		Replayed top;
		top.mesh = std::move(D.nodes[at].mesh);   // lent to the splits, not copied
		split_down(top, P);
		D.nodes[at].mesh = std::move(top.mesh);
		std::vector<std::pair<int, Replayed*>> todo{{at, &top}};
		while (!todo.empty()) {
			const auto [id, r] = todo.back();
			todo.pop_back();
			const Node& pn = P.nodes[r->pid];
			Node&       n  = D.nodes[id];
			n.concavity           = pn.concavity + e;
			n.hull_distance       = pn.hull_distance;
			n.hull_distance_bound = pn.hull_distance_bound + e;
			n.notch               = pn.notch;
			n.notch_count         = pn.notch_count;
			n.cavities            = pn.cavities;
			n.volume              = signed_volume(n.mesh);
			if (pn.child[0] < 0) reached[r->pid] = id;
			if (!r->child[0]) {
				leaves.push_back(id);
				continue;
			}
			n.has_plane = !pn.solids;
			n.solids    = pn.solids;
			n.plane     = pn.plane;
			n.cut_at    = pn.cut_at;
			n.hole_cut  = pn.hole_cut;
			const std::string path = n.path;
			for (int s = 0; s < 2; ++s) {
				Node c;
				c.parent = id;
				c.path   = path + char('0' + s);
				c.mesh   = std::move(r->child[s]->mesh);
				D.nodes.push_back(std::move(c));
				D.nodes[id].child[s] = (int) D.nodes.size() - 1;
			}
			for (int s = 1; s >= 0; --s) todo.push_back({D.nodes[id].child[s], r->child[s].get()});
		}
		std::sort(leaves.begin(), leaves.end(), [&](int a, int b) { return D.nodes[a].path < D.nodes[b].path; });
	}

	// The proxy node's split made on the solid's node: the same plane through the same region, or the
	// same solids apart. False if it does not split the solid's node in two parts with volume.
	static bool split_like(const TriMesh& mesh, const Decomposition& P, const Node& pn, std::array<TriMesh, 2>& parts)
	{
		if (pn.solids) return split_solids(mesh, P.nodes[pn.child[0]].mesh, parts);
		SplitOutcome so;
		try {
			if (!separate(mesh, pn.plane, pn.cut_at, so)) return false;
		}
		catch (const Error&) {
			return false;
		}
		const double v = signed_volume(mesh);
		for (const TriMesh& p : so.parts)
			if (!(signed_volume(p) > 1e-5 * v)) return false;
		parts = std::move(so.parts);
		return true;
	}

	// A search of leaf `at` (its root is `at` itself, its merged parts after its tree) hung into the tree
	// below it.
	void graft(int at, Decomposition& sub)
	{
		std::vector<int> id(sub.nodes.size(), at);
		const std::string base = D.nodes[at].path;
		for (size_t k = 1; k < sub.nodes.size(); ++k) {
			id[k] = (int) D.nodes.size();
			D.nodes.push_back(std::move(sub.nodes[k]));
			D.nodes.back().path = base + D.nodes.back().path.substr(1);
		}
		for (size_t k = 1; k < sub.nodes.size(); ++k) renumber(D.nodes[id[k]], id);
		Node& r = sub.nodes[0];
		renumber(r, id);
		r.parent = D.nodes[at].parent;
		r.path   = base;
		r.mesh   = std::move(D.nodes[at].mesh);
		D.nodes[at] = std::move(r);
	}
};

} // namespace

bool better_plan(const Decomposition& a, const Decomposition& b, double tau)
{
	const auto needed = [tau](const Decomposition& P) {
		size_t n = 0;
		for (int i : P.parts()) n += certified(P.nodes[i], tau) ? 1 : 2;
		return n;
	};
	const size_t na = needed(a), nb = needed(b);
	if (na != nb) return na < nb;
	return fewer_parts(a, b);
}

Decomposition search(const Solid& solid, const DecomposeOptions& o, const ProxySettings& ps, MergeMemo* memo,
                     MeasureMemo* measures)
{
	return ProxySearch(o, ps, memo, measures).run(solid);
}

} // namespace acd
