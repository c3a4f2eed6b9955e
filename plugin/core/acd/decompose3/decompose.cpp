#include "acd/decompose3/decompose.h"
#include "acd/decompose3/cut_planes.h"
#include "acd/hull/hull_reach.h"
#include "acd/decompose3/measure_memo.h"
#include "acd/decompose3/merge.h"
#include "acd/decompose3/proxy_search.h"
#include "acd/decompose3/relay.h"
#include "acd/mesh/parallel.h"
#include "acd/recursion/recursion.h"
#include "acd/mesh/measures.h"
#include "acd/solid/solid.h"
#include "acd/recursion/hole_order.h"

#include <Eigen/Eigenvalues>

#include <CGAL/Cartesian_d.h>
#include <CGAL/Min_sphere_of_points_d_traits_3.h>
#include <CGAL/Min_sphere_of_spheres_d.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <queue>
#include <set>
#include <sstream>
#include <unordered_map>
#include <unordered_set>
#include <thread>

namespace acd {

// The recursion's hole count of a 3D node: its cavities.
int holes_in(const Node& n)
{
	return n.cavities;
}

namespace {

// The faces of each cavity (a shell of negative volume) of a solid.
std::vector<std::vector<int>> cavity_faces(const TriMesh& m)
{
	int                           n = 0;
	const std::vector<int>        comp = face_components(m, &n);
	std::vector<std::vector<int>> shell(n);
	for (int f = 0; f < (int) m.F.size(); ++f) shell[comp[f]].push_back(f);
	std::vector<std::vector<int>> out;
	if (n < 2) return out;
	for (auto& faces : shell) {
		TriMesh sh;
		sh.V = m.V;
		for (int f : faces) sh.F.push_back(m.F[f]);
		if (signed_volume(sh) < 0) out.push_back(std::move(faces));
	}
	return out;
}

// The solid without its cavities (the same vertex array; unused vertices are harmless to the hull
// only if dropped, so they are).
TriMesh outer_surface(const TriMesh& m, const std::vector<std::vector<int>>& cavities)
{
	std::vector<char> drop(m.F.size(), 0);
	for (const auto& c : cavities)
		for (int f : c) drop[f] = 1;
	TriMesh          out;
	std::vector<int> id(m.V.size(), -1);
	for (int f = 0; f < (int) m.F.size(); ++f) {
		if (drop[f]) continue;
		Tri t;
		for (int k = 0; k < 3; ++k) {
			int& i = id[m.F[f][k]];
			if (i < 0) {
				i = (int) out.V.size();
				out.V.push_back(m.V[m.F[f][k]]);
			}
			t[k] = i;
		}
		out.F.push_back(t);
	}
	return out;
}

} // namespace

// What cutting a node needs from its measure (decompose.h); kept while the node waits to be cut. With
// keep_cavities only the outer surface is measured (a cavity never retracts to the hull).
struct Measured
{
	std::vector<std::vector<int>> cavities;   // faces of each cavity of the node's mesh
	TriMesh                       outer;      // keep_cavities with cavities: the measured surface
	Topology                      topo;
	ConvexHull                    hull;
	ConcavityReport               rep;
	// The hull's reach searched beyond notches deeper than tau (within_by_hull), once per measure.
	mutable std::mutex               reach_mutex;
	mutable std::optional<HullReach> by_hull;
	Measured(const TriMesh& m, bool keep_cavities, double tau, bool reach_always = false)
	    : cavities(cavity_faces(m)),
	      outer(keep_cavities && !cavities.empty() ? outer_surface(m, cavities) : TriMesh()),
	      topo(surface(m)), hull(surface(m).V), rep(measure_concavity(surface(m), topo, hull, tau, reach_always ? Reach::Always : Reach::WhereWithin))
	{
	}
	// What topo, hull and rep describe: the node's mesh `m` itself, or its outer surface. (The node's
	// mesh is passed in, not kept: nodes move when the tree grows.)
	const TriMesh& surface(const TriMesh& m) const { return outer.F.empty() ? m : outer; }
};

namespace {

// Whether the part measured by `ms` (its mesh `m`) is within tau by its hull alone, under
// merge_measure=hull_distance with the merge on: over tau by its notches, without a cavity, its hull's
// reach certified within tau to 1% of tau, as the cuts' measure certifies it. Its reach if so.
const HullReach* within_by_hull(const Measured& ms, const TriMesh& m, const DecomposeOptions& opt)
{
	if (!opt.merge_parts || opt.merge_measure != MergeMeasure::HullDistance) return nullptr;
	if (ms.rep.max_concavity <= opt.tau || !ms.cavities.empty() || !ms.outer.F.empty()) return nullptr;
	const double                bar = reach_bar(opt.tau);
	std::lock_guard<std::mutex> lock(ms.reach_mutex);
	if (!ms.by_hull) {
		// Most parts over tau by their notches reach beyond tau too: a bounded search finds a point past
		// the bar first; the full search then certifies the rest.
		HullReach hr = hull_reach(m, ms.hull, ms.rep.bridge, bar, 0.1 * opt.tau, 1e9, kReachPrefilter);
		if (hr.lower <= bar) hr = hull_reach(m, ms.hull, ms.rep.bridge, opt.tau, 0.01 * opt.tau, 0.02);
		ms.by_hull = hr;
	}
	return ms.by_hull->upper <= bar ? &*ms.by_hull : nullptr;
}

// A node's measures from its mesh's; its notch is kept when the mesh has none.
void take_measures(Node& n, const Measured& ms)
{
	n.concavity           = ms.rep.max_concavity;
	n.hull_distance       = ms.rep.hull_reach;
	n.hull_distance_bound = ms.rep.hull_reach_bound;
	n.volume              = signed_volume(n.mesh);
	n.notch_count         = ms.rep.notches;
	n.cavities            = (int) ms.cavities.size();
	n.hull_certified      = false;   // a merge that measured the reach beyond the notches says otherwise
	if (ms.rep.max_vertex >= 0) n.notch = ms.surface(n.mesh).V[ms.rep.max_vertex];
}

} // namespace

void renumber(Node& n, const std::vector<int>& id)
{
	const auto map = [&](int k) { return k < 0 ? -1 : id[k]; };
	n.parent   = map(n.parent);
	n.child[0] = map(n.child[0]), n.child[1] = map(n.child[1]);
	n.part     = map(n.part);
	for (int& l : n.merged) l = map(l);
}

std::vector<int> Decomposition::leaves() const
{
	std::vector<int> l;
	for (int i = 0; i < (int) nodes.size(); ++i)
		if (nodes[i].leaf()) l.push_back(i);
	std::sort(l.begin(), l.end(), [&](int a, int b) { return nodes[a].path < nodes[b].path; });
	return l;
}

std::vector<int> Decomposition::parts() const
{
	std::vector<int> p;
	for (int i = 0; i < (int) nodes.size(); ++i)
		if ((nodes[i].leaf() && nodes[i].part < 0) || !nodes[i].merged.empty()) p.push_back(i);
	std::sort(p.begin(), p.end(), [&](int a, int b) { return nodes[a].path < nodes[b].path; });
	return p;
}

double Decomposition::max_part_concavity() const
{
	double c = 0;
	for (int i : parts()) c = std::max(c, nodes[i].concavity);
	return c;
}

double Decomposition::max_hull_distance() const
{
	double c = 0;
	for (int i : parts()) c = std::max(c, nodes[i].hull_distance);
	return c;
}

bool Decomposition::certified(int id) const
{
	return acd::certified(nodes[id], tau);
}

bool Decomposition::tau_convex() const
{
	for (int i : parts())
		if (!certified(i)) return false;
	return kept_cavities == 0 && !max_parts_reached && !time_limit_reached;
}

namespace {

// A candidate plane split and scored.
struct Trial
{
	SplitOutcome so;
	// Its parts' measures (the paper's measure itself, the one the recursion uses): the picked
	// plane's become its children's, not measured again.
	std::shared_ptr<const Measured> measures[2];
	bool         ok = false;
	bool         crosses = false;   // keep_cavities: the plane cuts through a kept cavity
	double       score = 0, sum = 0;
	double       need = 0;          // the parts its halves are estimated to need (needs())
	int          sliver = -1;       // the side a rejected plane shaved off
	double       smaller = 0;       // the smaller side's share of the volume
};

// One node's cut: its target (the most concave notch, or a cavity), the candidate planes, their trials.
struct Cut
{
	int                id   = -1;
	int                hole = -1;   // the cavity cut, or -1 for the notch
	Vec3               notch = Vec3::Zero();
	std::vector<Plane> planes;
	std::vector<Trial> trials;
	bool               first_fit  = false;   // try planes in order, keep the first that splits
	bool               by_section = false;   // score by the cut's cross-section (MinSection)
	bool               complete   = false;   // the planes are already all the notch offers
	bool               widen      = false;   // none splits: score all the notch offers before halving
	bool               stalled = false;      // the node's own cut made no progress: this one must
	int                pick = -1;
};

// Approx_CD for a solid, as named stages; the recursion's queue and limits are shared with 2D.
class Driver : public Driving<Driver, Decomposition, DecomposeOptions>
{
public:
	Driver(const DecomposeOptions& opt, MeasureMemo* memo)
	    : Driving(opt, opt.hole_handling == HoleHandling::KeepCavities, kMaxDepth), memo(memo)
	{
	}

	Decomposition run(const Solid& solid, MeasuredPtr root)
	{
		const std::vector<int> roots = root_nodes(solid);
		for (int id : roots) measure_node(id, roots.size() == 1 ? root : nullptr);
		return finish(roots, &Decomposition::kept_cavities);
	}

	// One node: its target, candidate planes, their trials, the pick; the parts added.
	int cut(int id)
	{
		if (stop_by_hull(id)) return 0;
		Cut c;
		c.id = id;
		choose_target(c);
		candidate_planes_for(c);
		unstall(c);
		try_planes(c);
		pick_plane(c);
		widen(c);
		refine_neck(c);
		if (c.pick < 0 && halved_before(id) && drop_film(c)) return 0;
		if (c.pick < 0 && halve(c)) halved.insert(id);
		if (c.pick < 0 && drop_film(c)) return 0;
		return accept(c);
	}

	void forget(int id) { measured[id].reset(); }

private:
	// Under merge_measure=hull_distance a node whose hull stays within tau of it is a part as it is,
	// though its notches lie deeper (a slot narrower than tau, a low boss): the merge would unite its
	// pieces again by the same certificate, so cutting it would only cost time and parts.
	bool stop_by_hull(int id)
	{
		if (!acd::stop_by_hull(D.nodes[id], *measured[id], opt)) return false;
		measured[id].reset();
		return true;
	}

	MeasureMemo* const                           memo;       // measures shared with another search (or none)
	std::vector<std::shared_ptr<const Measured>> measured;   // kept while a node waits to be cut
	std::unordered_map<int, int>           films;      // per node: films dropped (bounded)
	std::unordered_set<int>                halved;     // nodes cut by halve()

	int add_node(TriMesh mesh, int parent, const std::string& path)
	{
		Node n;
		n.parent = parent;
		n.path   = path;
		n.mesh   = std::move(mesh);
		D.nodes.push_back(std::move(n));
		measured.emplace_back();
		return (int) D.nodes.size() - 1;
	}

	// `ms`: the node's mesh already measured (as a scored trial's part), else measured here.
	void measure_node(int id, std::shared_ptr<const Measured> ms = nullptr)
	{
		Node& n = D.nodes[id];
		if (!ms) ms = measure(n.mesh);
		take_measures(n, *ms);
		if (rec.needs_cut(n)) measured[id] = std::move(ms);
	}

	// Several solids (disjoint shells): no notch lies between them, so the measure would call the
	// union convex. Split them off first, one per level (A | rest), keeping the tree binary. The
	// nodes left to cut.
	std::vector<int> root_nodes(const Solid& solid)
	{
		std::vector<TriMesh> solids;
		if (solid.shells > 1) solids = connected_solids(solid.mesh);
		if (solids.size() < 2) return {add_node(solid.mesh, -1, "0")};
		std::vector<int> out;
		int              node = add_node(solid.mesh, -1, "0");
		for (size_t k = 0; k + 1 < solids.size(); ++k) {
			Node& n  = D.nodes[node];
			n.volume = signed_volume(n.mesh);
			n.solids = true;
			const std::string path = n.path;
			TriMesh           rest;
			for (size_t j = k + 1; j < solids.size(); ++j) append(rest, solids[j]);
			const int a = add_node(std::move(solids[k]), node, path + '0');
			const int b = add_node(k + 2 < solids.size() ? std::move(rest) : std::move(solids[k + 1]), node, path + '1');
			D.nodes[node].child[0] = a;
			D.nodes[node].child[1] = b;
			out.push_back(a);
			if (k + 2 == solids.size()) out.push_back(b);
			node = b;
		}
		return out;
	}

	// A cavity is cut when holes go first, when the most concave notch lies on one, or when only
	// cavities are left; the deepest cavity (or the notch's) is the one cut.
	void choose_target(Cut& c) const
	{
		const TriMesh&  mesh = D.nodes[c.id].mesh;
		const Measured& ms   = *measured[c.id];
		if (keep || ms.cavities.empty()) return;
		int    deepest         = -1;
		bool   notch_on_cavity = false;
		double depth           = -1;
		for (int k = 0; k < (int) ms.cavities.size(); ++k)
			for (int f : ms.cavities[k])
				for (int v : mesh.F[f]) {
					notch_on_cavity |= v == ms.rep.max_vertex;
					if (ms.rep.vertex_concavity[v] > depth) depth = ms.rep.vertex_concavity[v], deepest = k;
				}
		if (opt.hole_order == HoleOrder::First || notch_on_cavity || D.nodes[c.id].concavity <= opt.tau) c.hole = deepest;
	}

	// Every plane the notch offers (Best's), bisector first.
	std::vector<Plane> all_planes(int id) const
	{
		const Measured& ms = *measured[id];
		return all_notch_planes(ms.surface(D.nodes[id].mesh), ms.topo, ms.hull, ms.rep, opt.candidate_planes);
	}

	void candidate_planes_for(Cut& c) const
	{
		const TriMesh&  mesh = D.nodes[c.id].mesh;
		const Measured& ms   = *measured[c.id];
		if (c.hole < 0) {
			c.notch = ms.surface(mesh).V[ms.rep.max_vertex];
			CutPlan plan = plan_notch_cut(ms.surface(mesh), ms.topo, ms.hull, ms.rep, opt.cut_plane_selection,
			                              opt.candidate_planes, by_need());
			c.planes     = std::move(plan.planes);
			c.first_fit  = plan.policy == CutPolicy::FirstFit;
			c.by_section = plan.policy == CutPolicy::BySection;
			c.complete   = plan.complete;
			c.widen      = plan.widen;
		}
		else {
			c.planes = cavity_planes(mesh, ms.cavities[c.hole], ms.hull, opt.hole_handling, opt.candidate_planes, c.notch);
			// The paper's plane first, others only if it cannot split; or all of them scored.
			c.first_fit = opt.hole_handling != HoleHandling::BestPlane;
		}
		c.trials.assign(c.planes.size(), Trial());
	}

	// Whether a plane cuts through a cavity (its faces on both sides).
	static bool crosses(const TriMesh& mesh, const std::vector<int>& cavity, const Plane& pl)
	{
		bool neg = false, pos = false;
		for (int f : cavity)
			for (int v : mesh.F[f]) (pl.eval(mesh.V[v]) > 0 ? pos : neg) = true;
		return neg && pos;
	}

	// A plane that takes a chip (volume va or vb, concavity a or b) itself over tau and leaves the rest
	// as concave as the node resolves nothing: two nodes to cut for one, and picked, it would be
	// picked again on the rest, chip after chip.
	bool chips(int id, double va, double vb, double a, double b) const
	{
		const bool   first = va < vb;
		const double chip = first ? a : b, rest = first ? b : a;
		return std::min(va, vb) < 1e-3 * D.nodes[id].volume && chip > opt.tau && rest >= 0.99 * D.nodes[id].concavity;
	}

	// A plane a hair above a face shaves off a film: a half far thinner than tau across the plane
	// (kFilm), which has the plane's footprint, not the part's depth. It resolves none of the part's
	// notches below the film, and the film, a shape with an outline and no thickness, may take as
	// many parts as its outline's own notches ask. The film's side, or -1.
	int film(const SplitOutcome& so, const Plane& pl) const
	{
		for (int s = 0; s < 2; ++s) {
			double thick = 0;
			for (const Vec3& v : so.parts[s].V) thick = std::max(thick, std::abs(pl.eval(v)));
			if (thick < kFilm * opt.tau) return s;
		}
		return -1;
	}

	// A mesh's measure, from the memo when another search made it.
	MeasuredPtr measure(const TriMesh& m) const
	{
		const auto make = [&] { return std::make_shared<const Measured>(m, keep, opt.tau); };
		return memo ? memo->find_or_make(m, opt.tau, keep, make) : make();
	}

	// A trial's part's concavity as the search weighs it: at tau where its hull alone certifies it
	// (within_by_hull: it will not be cut), as the merge would certify its pieces' union.
	double weight(const Trial& t, int s) const
	{
		const Measured& ms = *t.measures[s];
		return within_by_hull(ms, t.so.parts[s], opt) ? opt.tau : ms.rep.max_concavity;
	}

	// The trial's two parts measured (false: one of them is beyond `beat`, the other left unmeasured).
	// `both_cores` measures the two at once; otherwise the larger part goes first, as the deep notch
	// is more often there.
	bool measure_parts(Trial& t, double va, double vb, double beat, bool both_cores) const
	{
		const auto measure_part = [&](int s) { t.measures[s] = measure(t.so.parts[s]); };
		if (both_cores) {
			parallel_for(2, [&](size_t s) { measure_part((int) s); });
			return true;
		}
		const int larger = va < vb ? 1 : 0;
		measure_part(larger);
		if (!(weight(t, larger) < beat)) return false;
		measure_part(1 - larger);
		return true;
	}

	// Split the node by candidate i and, with `score`, measure the parts. Trials are independent
	// (each writes its own slot), so they run on all cores. A plane that cannot be picked unless it
	// scores below `beat` stops, not ok, as soon as one part reaches it.
	void trial(Cut& c, size_t i, bool score, double beat = INFINITY, bool both_cores = false) const
	{
		const TriMesh&  mesh = D.nodes[c.id].mesh;
		const Measured& ms   = *measured[c.id];
		const double    v0   = D.nodes[c.id].volume;
		Trial&          t    = c.trials[i];
		t                    = Trial();
		if (!separate(mesh, c.planes[i], c.notch, t.so)) return;
		// A plane that grazes the part shaves off a sliver and resolves nothing.
		const double va = signed_volume(t.so.parts[0]), vb = signed_volume(t.so.parts[1]);
		t.smaller       = std::min(va, vb) / v0;
		if (va < 1e-5 * v0 || vb < 1e-5 * v0) {
			t.sliver = va < vb ? 0 : 1;
			return;
		}
		if (const int f = film(t.so, t.so.plane); f >= 0) {
			t.sliver = f;
			return;
		}
		if (keep)
			for (const auto& cav : ms.cavities) t.crosses |= crosses(mesh, cav, c.planes[i]);
		if (!score) {
			t.ok = true;
			return;
		}
		if (c.by_section) {
			t.score = t.so.cap_area;
			t.ok    = true;
			return;
		}
		try {
			if (!measure_parts(t, va, vb, beat, both_cores)) return;
			const double a = weight(t, 0), b = weight(t, 1);
			if (chips(c.id, va, vb, a, b)) {
				t.sliver = va < vb ? 0 : 1;
				return;
			}
			t.score = std::max(a, b);
			t.sum   = a + b;
			t.need  = needs(a) + needs(b);
			t.ok    = true;
		}
		catch (const Error&) {   // a part with no volume
		}
	}

	// A cut that takes a small piece off and leaves the same notch as deep (a notch on a thin shell,
	// where the bisector runs along the surface) resolves nothing, and the rest would be cut the same
	// way, piece after piece, down to the depth bound. A node made by such a cut must progress: its
	// candidates, the principal planes through its centroid among them, are all scored, and only
	// those that take a real piece off or leave it clearly less concave may be picked.
	bool stalled(int id) const
	{
		const Node& n = D.nodes[id];
		if (n.parent < 0 || D.nodes[n.parent].solids) return false;
		const Node& p = D.nodes[n.parent];
		return n.volume >= 0.99 * p.volume && n.concavity >= 0.99 * p.concavity && (n.notch - p.notch).norm() <= opt.tau;
	}

	bool by_need() const { return opt.pick_rule == PickRule::PartsNeeded; }

	// The parts a half of concavity c is estimated to need: one within tau; beyond it at least two,
	// and one more for each doubling of c (a cut roughly halves what it resolves).
	double needs(double c) const { return c <= opt.tau ? 1 : 2 + std::log2(c / opt.tau); }

	// A plane beats the bisector's need n0 only if its own is below n0 - kNeedMargin; as either half
	// needs at least one part, a half measured at this concavity or more already rules it out.
	double need_beat(double n0) const
	{
		const double target = n0 - kNeedMargin - 1;
		if (target <= 1) return 0;
		if (target <= 2) return opt.tau;
		return opt.tau * std::exp2(target - 2);
	}

	bool progresses(const Cut& c, const Trial& t) const
	{
		return t.smaller >= 0.01 || t.score < 0.99 * D.nodes[c.id].concavity;
	}

	void unstall(Cut& c) const
	{
		if (c.hole >= 0 || !stalled(c.id)) return;
		const TriMesh&  mesh = D.nodes[c.id].mesh;
		const Measured& ms   = *measured[c.id];
		c.stalled            = true;
		c.first_fit = c.by_section = false;
		if (!c.complete) {
			const auto more = all_planes(c.id);
			c.planes.insert(c.planes.end(), more.begin(), more.end());
		}
		const Vec3 centre = surface_moments(mesh, Vec3::Zero()).centroid;
		for (int k = 0; k < 3; ++k) c.planes.push_back(through(centre, ms.rep.frame.axes.row(k).transpose()));
		c.trials.assign(c.planes.size(), Trial());
	}

	// A notch charged with its bridge's reach (no vertex shows that depth) has a dihedral angle that
	// need not point across the reach: its plane stands unless it only shaves a tau-convex sliver
	// off and leaves the rest about as concave.
	void try_planes(Cut& c) const
	{
		const bool reach = c.hole < 0 && measured[c.id]->rep.reach_cut;
		if (c.first_fit) {
			// The paper's plane first; the others only if it cannot split.
			int fit = -1;
			for (size_t i = 0; i < c.planes.size() && fit < 0; ++i) {
				trial(c, i, reach);
				if (c.trials[i].ok && !c.trials[i].crosses) fit = (int) i;
			}
			const auto shaves = [&](const Trial& t) {
				return t.sum - t.score <= opt.tau && t.score >= 0.9 * D.nodes[c.id].concavity;
			};
			if (reach && (fit < 0 || shaves(c.trials[fit]))) c.first_fit = false;
		}
		if (c.first_fit) return;
		if (!bisector_stands(c)) {
			parallel_for(c.planes.size(), [&](size_t i) { trial(c, i, true); });
			return;
		}
		// The bisector first: the others need only be scored far enough to see whether they beat it.
		trial(c, 0, true, INFINITY, true);
		const Trial& t0   = c.trials[0];
		const double beat = !t0.ok || t0.crosses ? INFINITY : by_need() ? need_beat(t0.need) : kClearlyLess * t0.score;
		if (!(beat > 0)) return;   // no part weighs below 0: none can beat the bisector
		parallel_for(c.planes.size() - 1, [&](size_t i) { trial(c, i + 1, true, beat); });
	}

	// Whether pick_plane keeps candidate 0, the bisector, unless another scores clearly less.
	static bool bisector_stands(const Cut& c) { return c.hole < 0 && !c.by_section && !c.stalled && c.planes.size() > 1; }

	// By the worse half (the paper's greedy rule) or by the parts both halves are estimated to need
	// (a cut that leaves one half within tau is worth more than the worse half's concavity shows).
	// The paper's bisector plane (candidate 0) stands unless another leaves clearly (10%) less
	// concavity, or clearly (half a part) fewer parts to make: greedy scores alone would rather shave
	// small arms off one by one. Among the others, scores within a hair (planes are nudged ~1e-7 of
	// the size off vertices) are ties, settled by the total concavity.
	void pick_plane(Cut& c) const
	{
		const double hair = 1e-6 * extent(D.nodes[c.id].mesh.V);
		const auto&  T    = c.trials;
		int          pick = -1;
		for (const bool allow_crossing : {false, true}) {   // planes that spare kept cavities first
			for (int i = 0; i < (int) T.size(); ++i) {
				const Trial& t = T[i];
				if (!t.ok || (t.crosses && !allow_crossing) || (c.stalled && !progresses(c, t))) continue;
				if (by_need() && !c.by_section) {
					if (pick < 0 || t.need < T[pick].need - 1e-6 || (t.need <= T[pick].need + 1e-6 && t.score < T[pick].score - hair)) pick = i;
					continue;
				}
				if (pick < 0 || t.score < T[pick].score - hair || (t.score <= T[pick].score + hair && t.sum < T[pick].sum - hair))
					pick = i;
			}
			if (pick >= 0) break;
		}
		// For a notch (not a cavity, whose planes are all scored alike): see above.
		if (c.hole < 0 && !c.by_section && pick > 0 && T[0].ok && !T[0].crosses && !(c.stalled && !progresses(c, T[0])) &&
		    (by_need() ? !(T[pick].need < T[0].need - kNeedMargin) : !(T[pick].score < kClearlyLess * T[0].score)))
			pick = 0;
		c.pick = pick;
	}

	// At a sharp edge no plane of the edge splits (each shaves a sliver off): the notch's other
	// planes are scored, as the bisector falls back to them, before the part is halved.
	void widen(Cut& c) const
	{
		if (c.pick >= 0 || c.hole >= 0 || c.stalled || !c.widen) return;
		const auto   more = all_planes(c.id);
		const size_t from = c.planes.size();
		c.planes.insert(c.planes.end(), more.begin() + std::min<size_t>(1, more.size()), more.end());
		c.trials.resize(c.planes.size());
		parallel_for(c.planes.size() - from, [&](size_t i) { trial(c, from + i, true); });
		pick_plane(c);
	}

	// The fan samples the section's area every pi/K: the parabola through the smallest and its
	// neighbours puts the neck between samples, so the plane turns smoothly as the shape does.
	void refine_neck(Cut& c) const
	{
		if (!c.by_section || c.pick < 0 || measured[c.id]->rep.max_bridge < 0) return;
		const int    K = (int) c.planes.size();
		const Trial &l = c.trials[(c.pick + K - 1) % K], &r = c.trials[(c.pick + 1) % K];
		const double curv = l.score - 2 * c.trials[c.pick].score + r.score;
		if (K < 3 || !l.ok || !r.ok || !(curv > 0)) return;
		const double phi  = 0.5 * (l.score - r.score) / curv * M_PI / K;
		const Vec3   axis = c.planes[0].n.cross(c.planes[1].n).normalized(), n = c.planes[c.pick].n;   // the fan's
		c.planes.push_back(through(c.notch, std::cos(phi) * n + std::sin(phi) * axis.cross(n)));
		c.trials.emplace_back();
		trial(c, c.planes.size() - 1, true);
		if (c.trials.back().ok && !c.trials.back().crosses && c.trials.back().score < c.trials[c.pick].score)
			c.pick = (int) c.planes.size() - 1;
	}

	// No candidate splits (the notch sits where every plane through it shaves a sliver): halve the
	// part across its principal axes instead, so that it still shrinks towards tau. A curved strip
	// crossed in its middle falls in three pieces: then cut nearer an end along the same axes. True
	// if it did.
	bool halve(Cut& c) const
	{
		const TriMesh& mesh   = D.nodes[c.id].mesh;
		const Vec3     centre = surface_moments(mesh, Vec3::Zero()).centroid;
		for (const double frac : {0.5, 0.3, 0.7, 0.15, 0.85})
			for (int k = 0; k < 3 && c.pick < 0; ++k) {
				const Vec3 axis = measured[c.id]->rep.frame.axes.row(k).transpose();
				double     lo = INFINITY, hi = -INFINITY;
				for (const Vec3& v : mesh.V) lo = std::min(lo, axis.dot(v - centre)), hi = std::max(hi, axis.dot(v - centre));
				const double at = frac == 0.5 ? 0.0 : lo + frac * (hi - lo);
				c.planes.push_back(through(centre + at * axis, axis));
				c.trials.emplace_back();
				trial(c, c.planes.size() - 1, false);
				if (c.trials.back().ok) c.pick = (int) c.planes.size() - 1;
			}
		return c.pick >= 0;
	}

	// A half of a halved part that no plane splits either: a film is the likelier cause, which
	// halving would keep in one half, to be halved again, so it is dropped first.
	bool halved_before(int id) const { return D.nodes[id].parent >= 0 && halved.count(D.nodes[id].parent) > 0; }

	// Still none: the part may carry a film, two sheets of its surface a rounding error apart (a cut
	// plane a hair off a flat face leaves one). It holds no volume, yet its hull may reach far: drop
	// the widest film a plane shaves off, and measure the rest again. True if one was dropped.
	bool drop_film(Cut& c)
	{
		if (films[c.id] >= kMaxFilms) return false;
		int          drop   = -1;
		double       widest = 0;
		const double size   = extent(D.nodes[c.id].mesh.V);
		for (int i = 0; i < (int) c.trials.size(); ++i) {
			if (c.trials[i].sliver < 0) continue;
			const TriMesh& f = c.trials[i].so.parts[c.trials[i].sliver];
			const double   a = surface_area(f);
			if (std::abs(signed_volume(f)) <= 0.5e-6 * size * a && a > widest) widest = a, drop = i;
		}
		if (drop < 0) return false;
		Trial& t = c.trials[drop];
		++films[c.id];
		++D.films_dropped;
		D.film_volume += std::abs(signed_volume(t.so.parts[t.sliver]));
		D.nodes[c.id].mesh = std::move(t.so.parts[1 - t.sliver]);
		measured[c.id].reset();
		measure_node(c.id);
		rec.push(c.id);
		return true;
	}

	// The picked plane makes the node's two children (measured on two cores, then queued); no plane
	// leaves the node a leaf, reported uncut.
	int accept(Cut& c)
	{
		const int id = c.id;
		measured[id].reset();
		if (c.pick < 0) {
			D.nodes[id].uncut = true;
			return 0;
		}
		SplitOutcome best     = std::move(c.trials[c.pick].so);
		D.nodes[id].has_plane = true;
		D.nodes[id].plane     = best.plane;
		D.nodes[id].cut_at    = c.notch;
		D.nodes[id].hole_cut  = c.hole >= 0;
		D.hole_cuts += c.hole >= 0;
		const std::string path = D.nodes[id].path;
		for (int s = 0; s < 2; ++s) {
			const int child      = add_node(std::move(best.parts[s]), id, path + char('0' + s));
			D.nodes[id].child[s] = child;   // after add_node: it may move D.nodes
		}
		parallel_for(2, [&](size_t s) { measure_node(D.nodes[id].child[s], c.trials[c.pick].measures[s]); });
		for (int s = 0; s < 2; ++s) rec.push(D.nodes[id].child[s]);
		return 1;
	}

	static constexpr double kClearlyLess = 0.9;   // another plane's score must be below this times the bisector's
	static constexpr double kNeedMargin  = 0.5;   // or its parts needed this many below the bisector's
	static constexpr double kFilm = 0.05;     // a half thinner than this times tau across its plane is a film
	static constexpr size_t kMaxDepth = 96;   // tree depth (path length) past which a node stays uncut
	static constexpr int    kMaxFilms = 8;    // films dropped per node, so a node cannot loop
};

} // namespace

Decomposition cut_tree(const Solid& solid, const DecomposeOptions& opt, MeasuredPtr root, MeasureMemo* memo)
{
	return Driver(opt, memo).run(solid, std::move(root));
}

MeasuredPtr measure_node(Node& n, bool keep_cavities, double tau, bool reach_always)
{
	n.notch = Vec3::Zero();
	auto ms = std::make_shared<const Measured>(n.mesh, keep_cavities, tau, reach_always);
	take_measures(n, *ms);
	return ms;
}

bool stop_by_hull(Node& n, const Measured& ms, const DecomposeOptions& opt)
{
	const HullReach* r = within_by_hull(ms, n.mesh, opt);
	if (!r) return false;
	n.hull_distance       = r->lower;
	n.hull_distance_bound = r->upper;
	n.hull_certified      = true;
	return true;
}

bool fewer_parts(const Decomposition& a, const Decomposition& b)
{
	if (a.parts().size() != b.parts().size()) return a.parts().size() < b.parts().size();
	return a.max_hull_distance() < b.max_hull_distance() - 1e-9;
}

bool better(const Decomposition& a, const Decomposition& b)
{
	if (a.tau_convex() != b.tau_convex()) return a.tau_convex();
	return fewer_parts(a, b);
}

namespace {

// The search under each pick rule (cut_search = thorough; fast: the first alone), the better kept. A
// greedy search's choices compound, so which rule leaves fewer parts shows only at the end. The two
// searches run side by side, each free to take the threads the other leaves idle (one large part's
// measure, a merge's last unions), and share what both measure: a measure one is making the other waits
// for. Reports go through the Relay (relay.h). With one thread the second search runs in the time the
// first left. A solid large enough to be searched on a proxy is
// searched once here: its proxy search grows both trees on the proxy and certifies only the better on
// the solid (proxy_search.h), where a second search would double the certificates.
Decomposition search_rules(const Solid& unit, const DecomposeOptions& opt)
{
	DecomposeOptions o = opt;
	o.pick_rule        = PickRule::WorseHalf;
	const bool both    = opt.cut_search == CutSearch::Thorough && opt.max_parts == 0 &&
	                  unit.mesh.F.size() <= (size_t) ProxySettings().above;
	if (!both) return search(unit, o);
	const auto            start = std::chrono::steady_clock::now();
	const int             threads = (int) available_threads();
	MergeMemo             memo;       // the two trees share their first cuts, and their merges many unions
	MeasureMemo           measures;   // and the parts their planes make at the nodes they share
	std::array<Decomposition, 2> found;   // the second stays empty when the first left it no time
	Relay                        relay(opt.progress);
	auto one = [&](size_t k) {
		const ThreadLimit all(threads);
		DecomposeOptions  ok = o;
		ok.pick_rule         = k == 0 ? PickRule::WorseHalf : PickRule::PartsNeeded;
		if (opt.time_limit_seconds > 0) {
			ok.time_limit_seconds -= std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
			if (k == 1 && ok.time_limit_seconds <= 0) return;
		}
		if (opt.progress) ok.progress = relay.progress((int) k);
		{
			const Relay::Running running(relay);
			found[k] = search(unit, ok, {}, &memo, &measures);
		}
		relay.help_other();
	};
	parallel_for(2, one);
	if (found[1].nodes.empty() || !better(found[1], found[0])) return std::move(found[0]);
	found[1].pick_rule = PickRule::PartsNeeded;
	return std::move(found[1]);
}

} // namespace

Decomposition decompose(const Solid& solid, const DecomposeOptions& opt)
{
	if (!(opt.tau > 0) || !std::isfinite(opt.tau))
		throw Error(Error::InvalidOption, "tau must be a positive, finite length.");
	if (opt.max_parts < 0) throw Error(Error::InvalidOption, "max_parts must be 0 (unbounded) or positive.");
	if (opt.threads < 0) throw Error(Error::InvalidOption, "threads must be 0 (every core) or positive.");
	const ThreadLimit threads(opt.threads);

	// Work centred and at unit size: a mesh far from the origin (CAD, map coordinates) would
	// otherwise carry rounding errors hundreds of times larger than the same mesh at the origin,
	// and rounding decides near-ties. The tree is mapped back to model coordinates at the end.
	Vec3 c = Vec3::Zero();
	for (const Vec3& p : solid.mesh.V) c += p;
	c /= (double) solid.mesh.V.size();
	const double s = extent(solid.mesh.V);
	Solid        unit = solid;
	for (Vec3& p : unit.mesh.V) p = (p - c) / s;
	unit.volume /= s * s * s;
	DecomposeOptions o = opt;
	o.tau /= s;
	Decomposition D = search_rules(unit, o);
	D.tau = opt.tau;
	D.proxy_distance *= s;
	for (Node& n : D.nodes) {
		for (Vec3& p : n.mesh.V) p = p * s + c;
		n.concavity *= s;
		n.hull_distance *= s;
		n.hull_distance_bound *= s;
		n.volume *= s * s * s;
		n.notch = n.notch * s + c;
		n.cut_at = n.cut_at * s + c;
		n.plane.d = n.plane.d * s + n.plane.n.dot(c);
	}
	return D;
}

} // namespace acd
