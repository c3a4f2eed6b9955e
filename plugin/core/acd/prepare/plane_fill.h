// A hole in a surface made of planes (a CAD export with faces missing) closed by continuing the planes
// its rim runs on. Each plane's patch is bounded by the rim's stretches on it and by the creases where
// it meets the planes beside it, so a hole across an edge or a corner of the solid closes on that edge or
// corner, where a faired patch would round it. Holes whose rim does not run on a few planes are left to
// the fairing (fill_holes.h).
#pragma once

#include "acd/mesh/mesh.h"

#include <optional>
#include <vector>

namespace acd {

struct RimEdge
{
	int from, to;   // a border edge as its face runs it
	int face;
};

struct PlanePatch
{
	std::vector<Vec3> corners;   // new vertices: where three of the planes meet
	std::vector<Tri>  faces;     // >= 0 a vertex of the surface, < 0 corner -1 - i
};

// The patch of the hole whose border edges are `rim` (any order); `eps`: the distance within which a
// point lies on a plane. The rim is one cycle, or two openings that touch at a vertex between two fans
// of faces (each closed on its own). nullopt unless each cycle runs in stretches of two or more edges,
// each on the plane of its faces, and the planes meet inside the hole in one of these ways:
//  - every stretch on a plane of its own (up to 8): the planes meet at corners, three at a time, as a
//    triangulation of the polygon whose vertices are the stretches says; of all such ways, the one whose
//    corners lie near the hole and whose polygons are valid with the least area;
//  - else, between two stretches on one plane the rim visits either the same other plane at both ends (the
//    patch follows their crease) or two planes only (it turns at the corner the three make, near the hole);
// and unless each plane's patch is a simple polygon (or one that touches itself where the rim touches a
// crease the patch spans, at a vertex of the solid's edge) and they close the hole together. The patch
// is not checked against the surface beyond its rim.
// `about`: the faces about the hole, among which a vertex's fans are found (empty: all of m's).
std::optional<PlanePatch> plane_patch(const TriMesh& m, const std::vector<RimEdge>& rim, double eps,
                                      const std::vector<int>& about = {});

} // namespace acd
