// What a triangle mesh measures: volume, area, sizes, the pose frame, surface moments, point in solid,
// components. Nothing here changes a mesh.
#pragma once

#include "acd/mesh/mesh.h"

#include <vector>

namespace acd {

double signed_volume(const TriMesh& m);
double surface_area(const TriMesh& m);
// Adds `from`'s vertices and faces to `to` (disjoint union).
void append(TriMesh& to, const TriMesh& from);
// The points' axis-aligned bounding box (empty for no points), and its diagonal's length (0).
Eigen::AlignedBox3d bounding_box(const std::vector<Vec3>& pts);
double              bbox_diagonal(const std::vector<Vec3>& pts);
// The vertices with finite coordinates, and their bounding box (empty when there are none).
std::vector<Vec3>   finite_vertices(const TriMesh& m);
Eigen::AlignedBox3d finite_box(const TriMesh& m);
// A size that does not change with pose: twice the largest distance from the vertices' centroid
// (an axis-aligned box diagonal grows by up to sqrt(3) under rotation).
double extent(const std::vector<Vec3>& pts);

// The surface's principal axes, oriented by its own shape (each sign chosen so the surface's third
// moment along the axis is positive, the weakest axis completing a right-handed frame), so the frame
// turns with the object and does not depend on vertex or face order. Used to break exact ties
// (mirror-symmetric notches, equally reflex edges) the same way in every pose.
struct PoseFrame
{
	Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();   // rows: major, middle, minor axis
	Vec3            spread = Vec3::Zero();                 // the surface's variance along each axis
	double          tol = 0;                               // coordinates closer than this are equal
	// Axis k is the shape's own, the same in any pose: its variance stands apart from the other two
	// (on a square plate or a round bar two axes are any pair the pose and rounding make).
	bool distinct(int k, double gap = 0.05) const
	{
		for (int j = 0; j < 3; ++j)
			if (j != k && !(std::abs(spread[j] - spread[k]) > gap * std::max(spread[j], spread[k]))) return false;
		return true;
	}
	// Does a come before b? Compares coordinates along the axes in turn; false when all are equal.
	bool before(const Vec3& a, const Vec3& b) const
	{
		const Vec3 d = axes * (a - b);
		for (int i = 0; i < 3; ++i)
			if (std::abs(d[i]) > tol) return d[i] < 0;
		return false;
	}
};
PoseFrame pose_frame(const TriMesh& m);

// Area-weighted moments of a surface's faces (all, or those listed): their area, area centroid, and
// second moment about `o` (the exact integral of (x - o)(x - o)^T over each triangle), which follow
// the shape, not how densely its vertices sample it.
struct SurfaceMoments
{
	double          area     = 0;
	Vec3            centroid = Vec3::Zero();
	Eigen::Matrix3d second   = Eigen::Matrix3d::Zero();
};
SurfaceMoments surface_moments(const TriMesh& m, const Vec3& o, const std::vector<int>* faces = nullptr);

// Point-in-solid by ray parity (a closed mesh).
bool inside(const TriMesh& m, const Vec3& p);

// Parameters t where the line c + t a crosses the mesh, sorted, one per crossing. A line through an edge
// or a corner (an axis in a symmetry plane) meets several faces there, each within rounding of its
// border: each face takes hits a little beyond its border, so none is lost, and one crossing's hits
// are merged into one.
std::vector<double> line_crossings(const TriMesh& m, const Vec3& c, const Vec3& a);

// Connected components through shared edges; returns the component id of each face.
std::vector<int> face_components(const TriMesh& m, int* count);

// Rotation-invariant size used for percentages: the diameter of the smallest enclosing sphere.
double enclosing_diameter(const std::vector<Vec3>& pts);

} // namespace acd
