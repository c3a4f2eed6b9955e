/****************************************************************************
* meshlab-acd: approximate convex decomposition for MeshLab                  *
* GPL-3.0-or-later, like MeshLab.                                            *
****************************************************************************/
#include "messages.h"

namespace acdml {

QString message(const acd::Error& e)
{
	const QString n = QString::number(e.count);
	switch (e.code) {
	case acd::Error::PointCloud:
		return "The mesh is a point cloud (" + n + " vertices, no faces). Reconstruct a closed surface first, e.g. "
		       "with 'Surface Reconstruction: Screened Poisson' or 'Alpha Wrap'.";
	case acd::Error::RepeatedVertex:
		return n + " faces repeat a vertex. Run 'Remove Duplicate Faces' and 'Remove Zero Area Faces' "
		           "(meshing_remove_null_faces) first.";
	case acd::Error::ZeroArea:
		return n + " faces have zero area. Run 'Remove Zero Area Faces' (meshing_remove_null_faces) first.";
	case acd::Error::DuplicateFaces:
		return n + " faces duplicate other faces. Run 'Remove Duplicate Faces' (meshing_remove_duplicate_faces) first.";
	case acd::Error::OpenMesh:
		return "The mesh is open: it has " + n + " boundary edges. The decomposition needs a closed (watertight) "
		       "solid: set preprocessing to 'auto' (welds or alpha-wraps it; CLI --preprocessing auto), or close "
		       "the holes with 'Close Holes' (meshing_close_holes).";
	case acd::Error::NonManifoldEdges:
		return "The mesh has " + n + " non-manifold edges (shared by more than two faces). Set preprocessing to "
		       "'auto' (CLI --preprocessing auto), or repair it with 'Repair non Manifold Edges' "
		       "(meshing_repair_non_manifold_edges).";
	case acd::Error::Misoriented:
		return "The mesh's faces are not consistently oriented (" + n + " edges are used twice in the same "
		       "direction). Run 'Re-Orient all faces coherently' (meshing_re_orient_faces_coherently).";
	case acd::Error::OpenPart:
		return "A cut made a part that is not closed: the mesh intersects itself there. Use preprocessing = "
		       "alpha_wrap (or MeshLab's 'Alpha Wrap').";
	case acd::Error::NonManifoldBoundary:
		return "The mesh's boundary touches itself at a vertex (non-manifold boundary); repair it with 'Repair "
		       "non Manifold Vertices'.";
	case acd::Error::SelfIntersection:
		return "The mesh intersects itself (" + n + " pairs of faces cross away from shared corners). Repair it "
		       "with preprocessing = alpha_wrap or MeshLab's 'Alpha Wrap', or find the faces with 'Select Self "
		       "Intersecting Faces'.";
	default:
		if (e.kind == acd::Error::Internal) return QString("Internal error in the convex decomposition: ") + e.what();
		return QString::fromStdString(e.what());
	}
}

} // namespace acdml
