// Cut-plane strategies: for a part's most concave notch, the candidate planes of each strategy and how
// the driver tries them; for a cavity, the planes through it. A new strategy is a value of the enum, a
// row of cut_strategies() and a function in cut_planes.cpp.
#pragma once

#include "acd/decompose3/concavity.h"
#include "acd/mesh/labelled.h"

#include <vector>

namespace acd {

// Values are stable (scripts store labels, .mlx files the menu index of the table's rows).
enum class CutPlaneSelection
{
	Bisector,       // the paper: through the notch edge, bisecting its reflex dihedral angle
	Best,           // several planes through the notch (bisector, around its retraction direction,
	                // parallel to its bridge), keeping the one whose parts are least concave
	MinSection,     // (3D; polygons take Best) the neck: the plane through the notch and its retraction
	                // direction whose cut cross-section is smallest (steady under surface noise)
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

// How a plan's planes are tried.
enum class CutPolicy
{
	FirstFit,         // in order, the first plane that splits (the paper's plane, others only if it cannot)
	BisectorStands,   // every plane scored by its worse part; the first (the bisector) stands unless another
	                  // leaves clearly (10%) less concavity
	BySection         // every plane scored by the cut's cross-section (the neck)
};

// The strategies' labels (what scripts, the GUI and the command line say) and help, in menu order.
using CutStrategy = Labelled<CutPlaneSelection>;
const std::vector<CutStrategy>& cut_strategies();

// The notch's cut: its planes, best guess first, and how the driver tries them.
struct CutPlan
{
	std::vector<Plane> planes;
	CutPolicy          policy   = CutPolicy::FirstFit;
	bool               complete = false;   // already every plane all_notch_planes() gives: nothing to add
	bool               widen    = false;   // when none splits, score all_notch_planes() before halving
};

// The plan of strategy `sel` for the notch rep.max_vertex of `m` (`around`: planes in a fan). With `axes`,
// BisectorOrFace also scores the planes through the notch across the part's principal axes (the search
// that judges planes by the parts they leave: by the worse part alone they rarely win, and cost a trial).
CutPlan plan_notch_cut(const TriMesh& m, const Topology& topo, const ConvexHull& hull, const ConcavityReport& rep,
                       CutPlaneSelection sel, int around, bool axes = false);

// Every plane a notch offers (Best's), bisector first: what a stalled or unsplittable notch falls back on.
std::vector<Plane> all_notch_planes(const TriMesh& m, const Topology& topo, const ConvexHull& hull,
                                    const ConcavityReport& rep, int around);

// Planes through a cavity (its faces `cavity_faces` of `m`) for hole_handling, the paper's first:
// the principal plane (normal: the minor axis of the cavity surface's area-weighted covariance), then
// for BestPlane the two other principal planes and planes containing the direction from the cavity's
// centre to the nearest point of `hull` at `around` angles. `centre` receives the cavity's centre.
std::vector<Plane> cavity_planes(const TriMesh& m, const std::vector<int>& cavity_faces, const ConvexHull& hull,
                                 HoleHandling handling, int around, Vec3& centre);

} // namespace acd
