// Openings closed in the surface itself, the rest of the input kept exactly as it is. A hole whose rim
// runs on a few planes (a CAD export missing faces) is closed on those planes (plane_fill.h), so a hole
// across an edge or a corner closes on it. Any other is closed by CGAL's hole filling: triangulated,
// refined to the density of its rim and faired, so that the patch continues the surface's curvature and
// a hole punched into a curved surface closes along it instead of as a flat film. Each hole is filled
// in a few rings of faces about it, so the cost follows the holes, not the surface.
#pragma once

#include "acd/mesh/mesh.h"

#include <optional>

namespace acd {

struct FilledHoles
{
	TriMesh mesh;         // the surface (its faces turned to agree, faces naming a vertex twice dropped),
	                      // then the patches' vertices and faces
	size_t  first_patch = 0;   // mesh.F from here on are the patches' faces
	int     holes  = 0;   // holes filled (holes that touch at a corner count as one)
	int     planar = 0;   // of them, those closed on the planes their rims run on (plane_fill.h)
	int     faired = 0;   // of them, those faired; a faired patch that crosses the faces about it (a bulge
	                      // beside a sharp edge) is replaced by the flat one, triangulated and refined only
};

// nullopt when the surface is no edge-manifold, orientable triangle surface (an edge of three faces,
// pieces that cannot agree on an orientation), has no hole, more than `max_holes` holes or a hole of more
// than `max_rim` edges (the triangulation's cost grows with the cube of a rim's length), or a hole the
// triangulation cannot close. The result is not checked as a whole: a patch may still cross a far part of
// the surface (make_solid tells).
std::optional<FilledHoles> fill_holes(const TriMesh& surface, int max_holes = 200, int max_rim = 2000);

} // namespace acd
