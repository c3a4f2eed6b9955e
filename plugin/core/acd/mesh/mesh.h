// The core's vocabulary: points, triangle meshes, planes and the one error type every layer throws.
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
		NonManifoldBoundary,   // a planar mesh's boundary touches itself at a vertex
		SelfIntersection       // count: pairs of faces crossing (refused on request)
	};
	Error(Kind k, const std::string& msg, Code c = Unspecified, long n = 0)
	    : std::runtime_error(msg), kind(k), code(c), count(n)
	{
	}
	Kind kind;
	Code code;
	long count;
};

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

// Does face t name three vertices of m that exist and have finite coordinates? Measures skip the faces
// that do not; make_solid names them.
inline bool finite_face(const TriMesh& m, const Tri& t)
{
	for (int v : t)
		if (v < 0 || v >= (int) m.V.size() || !m.V[v].allFinite()) return false;
	return true;
}

// The plane through p with normal n (normalized here).
inline Plane through(const Vec3& p, Vec3 n)
{
	Plane pl;
	pl.n = n.normalized();
	pl.d = pl.n.dot(p);
	return pl;
}

} // namespace acd
