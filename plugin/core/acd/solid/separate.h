// Separate3D (the paper's Algorithms 4.2, 6.2, 6.3): split a solid by a plane into exactly two
// closed solids, cutting only the cross-section region that holds the notch (plus further regions
// only while the solid is still connected, as for a handle), and capping each cut region with its
// planar polygon with holes.
#pragma once

#include "acd/mesh/mesh.h"

namespace acd {

struct SplitOutcome
{
	std::array<TriMesh, 2> parts;            // parts[0] on the plane's negative side, parts[1] positive
	                                         // (one of them may reach across through regions left uncut)
	Plane                  plane;            // the plane actually used (possibly nudged off vertices)
	int                    regions_cut = 0;  // cross-section regions cut (1 unless a handle needed more)
	double                 cap_area = 0;
};

// Returns false when this plane cannot split the solid cleanly (no cross-section near the notch,
// a cap that cannot be triangulated, or more than two pieces); the caller then tries another plane.
bool separate(const TriMesh& m, const Plane& plane, const Vec3& notch, SplitOutcome& out);

// The solids of a closed mesh: each outward shell with the inward shells (cavities) directly inside
// it, largest volume first. Throws Error(InvalidInput) for a cavity that no shell holds.
std::vector<TriMesh> connected_solids(const TriMesh& m);

} // namespace acd
