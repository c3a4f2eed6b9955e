// Distances to a triangle surface: the nearest point on it and the largest distance of a point set
// from it, by CGAL's AABB tree (built once, queried in parallel).
#pragma once

#include "acd/mesh/mesh.h"

#include <memory>
#include <vector>

namespace acd {

class NearestOnSurface
{
public:
	// Faces with a corner out of range or not finite are left out; a surface without faces is at an
	// infinite distance from everything.
	explicit NearestOnSurface(const TriMesh& surface);
	~NearestOnSurface();
	NearestOnSurface(const NearestOnSurface&)            = delete;
	NearestOnSurface& operator=(const NearestOnSurface&) = delete;

	Vec3   closest(const Vec3& q) const;
	double distance(const Vec3& q) const;
	// The largest distance from `points` to the surface: from every point, or from `samples` evenly
	// spaced ones when there are more.
	double farthest(const std::vector<Vec3>& points, size_t samples = 200000) const;
	// The largest distance from another surface to this one, sampled at its vertices and at each face's
	// edge midpoints and centroid: a face spanning an opening lies farthest in its middle, where its
	// corners, on the rim, show nothing. Faces with a corner out of range or not finite are skipped.
	double farthest_on(const TriMesh& other) const;

private:
	struct Tree;
	std::unique_ptr<Tree> tree;
};

} // namespace acd
