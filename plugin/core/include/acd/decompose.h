// Approx_CD (the paper's Algorithm 4.1): cut the most concave notch until every part's concavity is
// at most tau. The result is the binary tree of cuts; its leaves are the parts.
#pragma once

#include "acd/concavity.h"
#include "acd/separate.h"

#include <functional>
#include <string>

namespace acd {

enum class CutPlaneSelection
{
	Bisector,   // the paper: through the notch edge, bisecting its reflex dihedral angle
	Best,       // several planes through the notch (bisector, around its retraction direction,
	            // parallel to its bridge), keeping the one whose parts are least concave
	MinSection, // (3D; polygons take Best) the neck: the plane through the notch and its retraction direction whose cut
	            // cross-section is smallest (steady under surface noise; the skeleton's choice)
	BisectorOrFace  // (3D) the bisector, or at a sharp notch edge (a CAD step, slot or flange) one of its two
	                // faces extended when that leaves clearly less concave parts; elsewhere as Bisector
};

// Cavities (closed inner shells) are the paper's hole boundaries: their notches can never retract to
// the hull, so they are resolved by cuts through the cavity itself.
enum class HoleHandling
{
	PrincipalPlane,   // the paper: the plane through the cavity's centre spanned by its two major axes
	BestPlane,        // the three principal planes and planes through the cavity towards the hull,
	                  // keeping the one whose parts are least concave
	KeepCavities      // never cut for a cavity: measure the outer surface only, report the cavities
};

enum class HoleOrder
{
	First,        // the paper (a hole's concavity is infinite): every cavity is cut before any notch
	ByConcavity   // a cavity's concavity is its depth below the hull; cut in turn with the notches
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
	bool              merge_parts = true;     // merge neighbouring parts while their union is tau-convex (merge.h)
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
	bool        uncut = false;     // leaf above tau because no plane split it (reported)
	bool        solids = false;    // split into its disjoint solids (first one | the rest), not by a plane
	int         cavities = 0;      // closed inner shells in this node's solid
	bool        hole_cut = false;  // the cut went through a cavity (hole_handling's plane)
	TriMesh     mesh;              // the node's solid
	std::vector<int> merged;       // a merged part (not in the cut tree): the leaves it unites, in path order
	int         part = -1;         // a leaf united into a merged part: that part's node
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
	bool              merge_time_limit_reached = false;   // merging stopped by the time limit (parts still certified)
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

// A part within tau by both measures (its hull within reach_bar) and not left uncut.
inline bool certified(const Node& n, double tau)
{
	return !n.uncut && n.concavity <= tau && n.hull_distance_bound <= reach_bar(tau);
}

// Level of detail from a finished tree, without recomputing: the nodes where the tree is cut when a
// piece may keep concavity up to `tau` (descend from the root while a node exceeds `tau`, holds a
// cavity that is not kept, or stands for several disjoint solids), or, with depth >= 0, the nodes at
// that depth (and leaves above it). Node ids in path order. By tau, a merged part replaces its leaves
// where the level keeps all of them (at the tree's own tau: the decomposition's parts).
std::vector<int> level_of_detail(const Decomposition& D, double tau, int depth = -1);

// The same by tau, and a node inside the tree is taken whole only if its hull is also certified within
// tau (hull_reach of the node rebuilt from the tree, to 1% of tau): the cuts never measured the hull
// of a node they split for a deeper notch, and a coarse part's hull may cover a hole its notches do not
// see (a ring's arc). `hull` gives the node's hull, or the rebuilt solid's when empty.
std::vector<int> level_of_detail_within(const Decomposition& D, double tau, const std::vector<TriMesh>& hull = {});

// The solid of node `id` rebuilt from the leaf meshes below it: the caps of the cuts inside the
// subtree are dropped, vertices welded, and the vertices that later cuts added on one side of a cap's
// rim are inserted into the other side's edges, so the result is closed again.
TriMesh rebuild_solid(const Decomposition& D, int id);

Decomposition decompose(const Solid& solid, const DecomposeOptions& options);

// Candidate cutting planes through the notch vertex `r` of mesh `m`, best guess first. `used`, if
// given, receives the selection they follow (BisectorOrFace at an edge that is not sharp: Bisector).
std::vector<Plane> candidate_planes(const TriMesh& m, const Topology& topo, const ConvexHull& hull,
                                    const ConcavityReport& rep, CutPlaneSelection sel, int around,
                                    CutPlaneSelection* used = nullptr);

// Planes through a cavity (its vertices `cavity` of `m`) for hole_handling, the paper's first:
// the principal plane (normal: the minor axis of the cavity surface's area-weighted covariance), then
// for BestPlane the two other principal planes and planes containing the direction from the cavity's
// centre to the nearest point of `hull` at `around` angles. `centre` receives the cavity's centre.
std::vector<Plane> cavity_planes(const TriMesh& m, const std::vector<int>& cavity_faces, const ConvexHull& hull,
                                 HoleHandling handling, int around, Vec3& centre);

// Rotation-invariant size used for percentages: the diameter of the smallest enclosing sphere.
double enclosing_diameter(const std::vector<Vec3>& pts);

} // namespace acd
