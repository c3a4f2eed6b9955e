// The paper's notch concavity (Section 6.1, Algorithm 6.1): the distance from a notch to the
// bridge of the pocket that holds it, with notches assigned to bridges by surface shortest paths.
#pragma once

#include "acd/hull/hull.h"
#include "acd/hull/hull_reach.h"
#include "acd/mesh/topology.h"
#include "acd/mesh/measures.h"

namespace acd {

struct ConcavityReport
{
	std::vector<double> vertex_concavity;   // per mesh vertex, model units; 0 on the hull
	std::vector<int>    vertex_bridge;      // hull facet a vertex's concavity was measured to, or -1
	int    notches  = 0;     // reflex edges
	int    bridges  = 0;     // hull facets not covered by the surface
	int    pockets  = 0;     // connected regions of surface faces not on the hull
	int    patches  = 0;     // pocket regions after the bridge-path partition
	double max_concavity = 0;   // over notch vertices
	int    max_vertex    = -1;  // the most concave notch vertex (-1: no notch)
	int    max_bridge    = -1;  // hull facet it retracts to
	PoseFrame frame;            // the part's frame that settled ties (reused for the cut's ties)
	double hull_reach = 0;        // largest distance from a bridge point to the surface found (see hull_reach.h)
	double hull_reach_bound = 0;  // no bridge point lies farther from the surface
	bool   reach_cut = false;     // max_concavity is the bridges' reach, charged to the nearest notch
	std::vector<char> bridge;     // per hull facet: a bridge (not covered by the surface)
};

// Which parts the bridges' reach is measured for: those whose notches lie within tau, every part, or
// none (the caller measures it later, with bridges_reach, from the report's `bridge`).
enum class Reach { WhereWithin, Always, Left };

// `m` must be a closed, edge-manifold, outward-oriented mesh (see make_solid) and `hull` its hull.
// A part's concavity is the larger of its notches' distances to their bridges and the bridges' reach
// beyond the surface, so it is never less than how far the part's hull stands off the part. With
// `tau` > 0 (model units) the reach is refined only as far as deciding against tau needs, for the parts
// `reach` names.
ConcavityReport measure_concavity(const TriMesh& m, const Topology& topo, const ConvexHull& hull, double tau = 0,
                                  Reach reach = Reach::WhereWithin);

// The bridges' reach as measure_concavity refines it: against tau (> 0) to 1% of tau, 2% above it; with
// tau 0 to 0.1% of the largest notch concavity `deepest`, which it is checked against.
HullReach bridges_reach(const TriMesh& m, const ConvexHull& hull, const std::vector<char>& bridge, double tau,
                        double deepest = 0);

// The concavity that reach charges its part with (at its nearest notch): with tau > 0, where the reach is
// not certified within tau, at least a hair over tau; with tau 0, the reach where it exceeds `deepest`.
// 0 where it charges nothing.
double reach_charge(const HullReach& reach, const ConvexHull& hull, double tau, double deepest = 0);

} // namespace acd
