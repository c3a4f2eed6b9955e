// Closed triangle meshes as the core sees them, and the checks that make them safe to decompose.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace acd {

using Vec3 = Eigen::Vector3d;
using Tri  = std::array<int, 3>;

struct TriMesh
{
	std::vector<Vec3> V;
	std::vector<Tri>  F;
};

// Every failure the core reports. `kind` lets hosts phrase the message (MeshLab turns all of them
// into MLException); the message itself already says what is wrong and what to do.
class Error : public std::runtime_error
{
public:
	enum Kind { InvalidInput, InvalidOption, Cancelled, Internal };
	Error(Kind k, const std::string& msg) : std::runtime_error(msg), kind(k) {}
	Kind kind;
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
	bool             flipped = false;       // the input was inside out and has been turned outward
	double           volume = 0;
};

// Throws Error(InvalidInput) naming the first problem found and a MeshLab filter that repairs it.
Solid make_solid(const TriMesh& input);

double signed_volume(const TriMesh& m);
double bbox_diagonal(const std::vector<Vec3>& pts);
// Connected components through shared edges; returns the component id of each face.
std::vector<int> face_components(const TriMesh& m, int* count);

// A plane n.x = d with unit normal n.
struct Plane
{
	Vec3   n = Vec3::UnitZ();
	double d = 0;
	double eval(const Vec3& p) const { return n.dot(p) - d; }
};

} // namespace acd
