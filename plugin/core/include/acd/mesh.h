// Closed triangle meshes as the core sees them, and the checks that make them safe to decompose.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>

#include <array>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace acd {

using Vec3 = Eigen::Vector3d;
using Tri  = std::array<int, 3>;

struct TriMesh
{
	std::vector<Vec3> V;
	std::vector<Tri>  F;
};

// Every failure the core reports. The message says what is wrong in the core's own terms; `code`
// and `count` let a host name its own repair (MeshLab's filters, a CLI option) for the input
// problems it can fix, `kind` how to phrase the rest.
class Error : public std::runtime_error
{
public:
	enum Kind { InvalidInput, InvalidOption, Cancelled, Internal };
	enum Code {
		Unspecified,
		PointCloud,            // count: vertices (no faces)
		RepeatedVertex,        // count: faces naming a vertex twice
		ZeroArea,              // count: faces
		DuplicateFaces,        // count: faces
		OpenMesh,              // count: boundary edges
		NonManifoldEdges,      // count: edges
		Misoriented,           // count: edges used twice in one direction
		OpenPart,              // a cut made an open part: the mesh crosses itself there
		NonManifoldBoundary    // a planar mesh's boundary touches itself at a vertex
	};
	Error(Kind k, const std::string& msg, Code c = Unspecified, long n = 0)
	    : std::runtime_error(msg), kind(k), code(c), count(n)
	{
	}
	Kind kind;
	Code code;
	long count;
};

// A validated solid: compact, finite, closed, 2-manifold along edges, consistently and outward
// oriented. Vertices shared by several fans (non-manifold vertices) are split into one copy per fan,
// so every later step can rely on edge-manifoldness. `source_vertex[i]` is the input index of V[i].
struct Solid
{
	TriMesh          mesh;
	std::vector<int> source_vertex;
	int              shells = 0;            // connected components (by edges)
	int              split_vertices = 0;    // non-manifold vertices that were split
	int              unreferenced_vertices = 0;
	bool             flipped = false;       // the input (or some shell) was inside out and has been turned
	int              reoriented_shells = 0; // shells whose orientation disagreed with their nesting
	int              cavities = 0;          // shells nested inside another an odd number of times
	long             self_intersections = 0;   // pairs of faces crossing away from shared corners
	double           volume = 0;
};

// Throws Error(InvalidInput) naming the first problem found (with its code and count).
Solid make_solid(const TriMesh& input);

// The pairs of faces that cross away from shared corners (corners within 1e-9 `diag` count as shared).
std::vector<std::pair<int, int>> self_crossings(const TriMesh& m, double diag);

double signed_volume(const TriMesh& m);
double surface_area(const TriMesh& m);
// Adds `from`'s vertices and faces to `to` (disjoint union).
void append(TriMesh& to, const TriMesh& from);
double bbox_diagonal(const std::vector<Vec3>& pts);
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
	double          tol = 0;                               // coordinates closer than this are equal
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

// Connected components through shared edges; returns the component id of each face.
std::vector<int> face_components(const TriMesh& m, int* count);

// A plane n.x = d with unit normal n.
struct Plane
{
	Vec3   n = Vec3::UnitZ();
	double d = 0;
	double eval(const Vec3& p) const { return n.dot(p) - d; }
	// Triangle t (of vertices V) lies on the plane: each corner within eps of it (a cut's cap face).
	bool holds(const std::vector<Vec3>& V, const Tri& t, double eps) const
	{
		return std::abs(eval(V[t[0]])) <= eps && std::abs(eval(V[t[1]])) <= eps && std::abs(eval(V[t[2]])) <= eps;
	}
};

} // namespace acd
