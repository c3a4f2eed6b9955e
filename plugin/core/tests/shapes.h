// Test solids built from their definition: boxes, extruded polygons, spheres, tori.
#pragma once

#include "acd/mesh/mesh.h"

namespace shapes {
using acd::TriMesh;
using acd::Vec3;
TriMesh box(Vec3 lo, Vec3 hi);
// Prism over a simple counter-clockwise polygon in the xy plane, from z0 to z1.
TriMesh extrude(const std::vector<Eigen::Vector2d>& poly, double z0, double z1);
TriMesh sphere(int subdivisions, double radius);
TriMesh torus(double R, double r, int nu, int nv);
// A solid of revolution about z: profile (r, z) from the bottom pole (r = 0) to the top pole (r = 0).
TriMesh lathe(const std::vector<Eigen::Vector2d>& profile, int nu);
TriMesh merge(const TriMesh& a, const TriMesh& b);
TriMesh inverted(TriMesh m);
// Every face split in four at its edges' midpoints (shared midpoints shared): the same shape, 4x the faces.
TriMesh subdivided(const TriMesh& m);
std::vector<Eigen::Vector2d> l_shape();   // (0,0)-(2,0)-(2,1)-(1,1)-(1,2)-(0,2)
std::vector<Eigen::Vector2d> u_shape();
std::vector<Eigen::Vector2d> slot_shape();   // a 3 x 2 block with a slot 0.2 wide and 1.6 deep
std::vector<Eigen::Vector2d> plus_shape();
// The plane n.x = d, n normalized.
acd::Plane plane(Vec3 n, double d);
} // namespace shapes
