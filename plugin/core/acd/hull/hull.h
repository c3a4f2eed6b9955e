// Convex hull of a point set, with coplanar hull triangles merged into facets (a cube's hull has 6
// facets, not 12 triangles) and fast distance queries to its boundary.
#pragma once

#include "acd/mesh/mesh.h"

#include <memory>

namespace acd {

class ConvexHull
{
public:
	// Throws Error(InvalidInput) when the points span no volume.
	explicit ConvexHull(const std::vector<Vec3>& points);
	~ConvexHull();
	ConvexHull(ConvexHull&&) noexcept;
	ConvexHull& operator=(ConvexHull&&) noexcept;

	// Hull vertices (positions, and their index in the input point array) and triangles, in an order that
	// depends on the points alone (vertices sorted, each triangle from its least corner, triangles sorted):
	// the same in every run and on any thread, as outputs must be.
	std::vector<Vec3> points;
	std::vector<int>  point_source;
	std::vector<Tri>  triangles;       // outward oriented, indices into `points`
	std::vector<int>  triangle_facet;  // which facet each triangle belongs to
	std::vector<std::vector<int>> facet_triangles;
	std::vector<Plane>            facet_plane;   // outward unit normal
	std::vector<double>           facet_area;
	double                        volume = 0;

	int facets() const { return (int) facet_plane.size(); }
	// Distance from p to the hull's boundary, and the triangle that realises it. A triangle `near`
	// p's nearest one (a mesh neighbour's, say) seeds the search: much faster than none (-1).
	double distance_to_boundary(const Vec3& p, int* triangle = nullptr, int near = -1, Vec3* closest = nullptr) const;
	std::vector<int> point_triangle;   // a triangle incident to each hull vertex
	// The facet among those touching triangle t's corners whose normal is closest to n: which facet
	// a surface face near t lies on, even when its centroid is nearest to a neighbouring facet.
	int facet_facing(int t, const Vec3& n) const;
	// Distance from p to one facet (a planar convex polygon).
	double distance_to_facet(const Vec3& p, int facet) const;
	// Hull as a mesh (vertices = hull vertices).
	TriMesh mesh() const;

private:
	void index_facets(const std::vector<int>& group);   // group: per triangle, its coplanar group
	void index_corners();
	std::vector<int> corner_start_, corner_tris_;   // CSR: hull vertex -> its triangles
	struct Tree;
	std::unique_ptr<Tree> tree_;
};

} // namespace acd
