// Approx_CD (the paper's Algorithm 4.1): cut the most concave notch until every part's concavity is
// at most tau. The result is the binary tree of cuts; its leaves are the parts.
#pragma once

#include "acd/decompose3/concavity.h"
#include "acd/decompose3/cut_planes.h"
#include "acd/solid/separate.h"
#include "acd/solid/solid.h"
#include "acd/recursion/hole_order.h"

#include <memory>
#include <functional>
#include <string>

namespace acd {

// How hard the cut search looks (cut_search): one greedy search, or one per pick rule, the better kept.
enum class CutSearch
{
	Thorough,
	Fast
};

// What a union of neighbouring parts must stay within tau by to be merged (merge_measure): how far its
// hull reaches beyond it, what a collision hull adds (and a part so within tau is not cut either: see
// stop_by_hull); or that and the cuts' own measure, every notch's concavity (a pocket the hull spans,
// such as a slot narrower than tau, is then cut apart).
enum class MergeMeasure
{
	HullDistance,
	Concavity
};

// What a candidate plane is judged by: its worse half's concavity (the paper's greedy rule), or the
// parts its two halves are estimated to need afterwards.
enum class PickRule
{
	WorseHalf,
	PartsNeeded
};

struct DecomposeOptions
{
	double            tau = 0;   // model units; > 0
	CutPlaneSelection cut_plane_selection = CutPlaneSelection::BisectorOrFace;
	int               max_parts = 0;          // 0 = unbounded
	int               candidate_planes = 6;   // planes around the retraction direction (Best)
	HoleHandling      hole_handling = HoleHandling::BestPlane;
	HoleOrder         hole_order = HoleOrder::First;
	double            time_limit_seconds = 0; // 0 = none; bounds the cuts and the merge after them
	bool              merge_parts = true;     // merge neighbouring parts while their union is within tau (merge.h)
	MergeMeasure      merge_measure = MergeMeasure::HullDistance;   // by which measure
	int               threads = 0;            // threads the decomposition may use (0: every core); the parts do not depend on it
	CutSearch         cut_search = CutSearch::Thorough;
	PickRule          pick_rule = PickRule::WorseHalf;   // one search's rule (set by cut_search's searches)
	// Called with a percentage and a short status; return false to cancel (throws Error(Cancelled)).
	std::function<bool(int, const char*)> progress;
};

struct Node
{
	int         parent = -1;
	int         child[2] = {-1, -1};
	std::string path;              // "0" for the root, parent's path + '0'/'1' for children
	double      concavity = 0;     // of this node's solid: the paper's measure, at least the hull's reach
	double      hull_distance = 0; // how far the node's hull reaches beyond it (attained; see hull_reach.h)
	double      hull_distance_bound = 0;   // and no farther than this
	double      volume = 0;
	int         notch_count = 0;   // reflex edges
	Vec3        notch = Vec3::Zero();   // most concave notch (meaningful if concavity > 0)
	bool        has_plane = false;      // internal node: the cut
	Plane       plane;
	Vec3        cut_at = Vec3::Zero();  // the point whose cross-section region the cut opened (separate's notch)
	bool        uncut = false;     // leaf above tau because no plane split it (reported)
	bool        solids = false;    // split into its disjoint solids (first one | the rest), not by a plane
	int         cavities = 0;      // closed inner shells in this node's solid
	bool        hole_cut = false;  // the cut went through a cavity (hole_handling's plane)
	TriMesh     mesh;              // the node's solid
	std::vector<int> merged;       // a merged part (not in the cut tree): the leaves it unites, in path order
	int         part = -1;         // a leaf united into a merged part: that part's node
	bool        hull_certified = false;   // a part within tau by its hull alone, its notches deeper (MergeMeasure::HullDistance: merged, or not cut)
	bool        leaf() const { return child[0] < 0 && merged.empty(); }
};

struct Decomposition
{
	std::vector<Node> nodes;        // nodes[0] is the root
	double            tau = 0;
	bool              max_parts_reached = false;
	bool              time_limit_reached = false;
	int               hole_cuts = 0;       // cuts made to resolve cavities
	int               kept_cavities = 0;   // cavities left in the parts (keep_cavities)
	int               films_dropped = 0;   // zero-thickness films cut off parts no plane could split
	double            film_volume = 0;     // the volume they held (rounding: near 0)
	int               merges = 0;          // neighbouring parts merged after the cuts
	int               proxy_searches = 0;  // searches run on a simplified copy (proxy_search.h)
	int               proxy_retries = 0;   // parts whose certificate failed on the original and were searched again
	int               proxy_faces = 0;     // the first proxy's faces (0: searched on the solid itself)
	double            proxy_distance = 0;  // its distance to the solid, measured (model units)
	bool              merge_time_limit_reached = false;   // merging stopped by the time limit (parts still certified)
	PickRule          pick_rule = PickRule::WorseHalf;    // the rule of the search kept
	// The cut tree's leaves in a stable order (by tree path).
	std::vector<int> leaves() const;
	// The parts: the leaves not merged and the merged parts, by their (first leaf's) path.
	std::vector<int> parts() const;
	double           max_part_concavity() const;
	double           max_hull_distance() const;   // over the parts
	bool             certified(int id) const;   // acd::certified(nodes[id], tau)
	// The certificate: every part certified, no cavity kept, no limit reached.
	bool             tau_convex() const;
};

// How far a certified hull may reach: tau and the 1% of tau the reach is refined to; the rest is rounding.
inline double reach_bar(double tau) { return 1.01 * tau * (1 + 1e-9); }

// A part within tau by both measures (its hull within reach_bar), or by its hull alone where it was
// merged by that measure, and not left uncut.
inline bool certified(const Node& n, double tau)
{
	return !n.uncut && (n.concavity <= tau || n.hull_certified) && n.hull_distance_bound <= reach_bar(tau);
}

// A merged part's certificate under `measure`: by MergeMeasure::HullDistance its hull alone may vouch for
// it (marked hull_certified), so its reach must have been measured beyond its notches (reach_always).
inline bool certify_merged(Node& n, double tau, MergeMeasure measure)
{
	n.hull_certified = measure == MergeMeasure::HullDistance && n.concavity > tau;
	return certified(n, tau);
}

Decomposition decompose(const Solid& solid, const DecomposeOptions& options);

// Of two searches of one solid, whether `a` is the better: certified first, then fewer_parts().
bool better(const Decomposition& a, const Decomposition& b);
// Whether `a` has the fewer parts, or as many and the nearer hulls (within rounding: a tie keeps the
// first).
bool fewer_parts(const Decomposition& a, const Decomposition& b);

// n's references to other nodes (parent, children, merged part, merged leaves) renumbered: old id k
// becomes id[k] (-1 stays -1).
void renumber(Node& n, const std::vector<int>& id);

// decompose()'s stages, for the proxy search (proxy_search.h). A node's measures from its mesh, as the
// cuts take them; the measure itself is returned, so that a part that fails the certificate is not
// measured again as the root of its own search. The cut tree of a solid centred and at unit size (no
// merge); `root`: the solid's mesh measured so already (with the same options), or none; `memo`:
// measures to take and keep (measure_memo.h), or none.
struct Measured;
using MeasuredPtr = std::shared_ptr<const Measured>;
class MeasureMemo;
MeasuredPtr   measure_node(Node& n, bool keep_cavities, double tau, bool reach_always = false);
// Under merge_measure=hull_distance (and the merge on) a part over tau by its notches whose hull stays
// within tau of it, measured to 1% of tau as the cuts' measure is, needs no cut: the merge would unite
// its pieces again by that certificate. True then, with n's hull distances set and n hull_certified.
// `ms`: n measured (measure_node); one shell without a cavity.
constexpr int kReachPrefilter = 2000;   // distance queries spent looking for a point beyond the bar first
bool          stop_by_hull(Node& n, const Measured& ms, const DecomposeOptions& options);
Decomposition cut_tree(const Solid& solid, const DecomposeOptions& options, MeasuredPtr root = nullptr,
                       MeasureMemo* memo = nullptr);

} // namespace acd
