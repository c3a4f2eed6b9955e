// The generalized winding number of a triangle surface (Jacobson et al. 2013), evaluated fast by a
// bounding-volume tree whose far nodes count as one dipole (Barill et al. 2018, first order): about 1
// inside a closed outward surface, 0 outside, and a smooth field across holes, soups and flipped
// patches, so that it tells what an open surface encloses.
#pragma once

#include "acd/mesh/mesh.h"

#include <vector>

namespace acd {

class WindingNumber
{
public:
	// Faces with a corner out of range or not finite are left out.
	explicit WindingNumber(const TriMesh& surface);
	double              at(const Vec3& q) const;
	std::vector<double> at(const std::vector<Vec3>& qs) const;   // in parallel, the same for any thread count

private:
	struct Node
	{
		Eigen::AlignedBox3d box;
		Vec3                normal = Vec3::Zero();   // sum of the faces' area vectors
		Vec3                centre = Vec3::Zero();   // their area-weighted centroid
		double              radius = 0;              // of a ball about centre holding them
		int                 first = 0, count = 0;    // faces tri[first, first + count)
		int                 left = -1, right = -1;   // children (-1: a leaf)
	};
	std::vector<std::array<Vec3, 3>> tri;
	std::vector<Node>                nodes;
	int                              build(int first, int count);
};

} // namespace acd
