#include "acd/hull/hull.h"
#include "acd/hull/hull_traits.h"
#include "acd/mesh/disjoint_sets.h"
#include "acd/mesh/measures.h"

#include <CGAL/AABB_traits_3.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <unordered_map>

namespace acd {

namespace {
using K         = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point     = K::Point_3;
using Triangle  = K::Triangle_3;
using SMesh     = CGAL::Surface_mesh<Point>;
using TriVec    = std::vector<Triangle>;
using Primitive = CGAL::AABB_triangle_primitive_3<K, TriVec::const_iterator>;
using AABB      = CGAL::AABB_tree<CGAL::AABB_traits_3<K, Primitive>>;

Point to_cgal(const Vec3& p) { return Point(p.x(), p.y(), p.z()); }
Vec3  to_vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }

struct BitsHash
{
	size_t operator()(const Point& p) const
	{
		const double c[3] = {p.x(), p.y(), p.z()};
		size_t       h    = 1469598103934665603ull;
		for (double x : c) {
			unsigned long long b;
			std::memcpy(&b, &x, 8);
			h = (h ^ b) * 1099511628211ull;
		}
		return h;
	}
};

} // namespace

struct ConvexHull::Tree
{
	TriVec tris;
	AABB   aabb;
};

ConvexHull::~ConvexHull()                                = default;
ConvexHull::ConvexHull(ConvexHull&&) noexcept            = default;
ConvexHull& ConvexHull::operator=(ConvexHull&&) noexcept = default;

namespace {

// CGAL's hull of the points, and where each distinct point first occurs in the input.
SMesh cgal_hull(const std::vector<Vec3>& input, std::unordered_map<Point, int, BitsHash>& index)
{
	std::vector<Point> pts;
	pts.reserve(input.size());
	index.reserve(input.size());
	for (int i = 0; i < (int) input.size(); ++i) {
		pts.push_back(to_cgal(input[i]));
		index.emplace(pts.back(), i);
	}
	if (index.size() < 4) throw Error(Error::InvalidInput, "Fewer than 4 distinct points: no volume.");
	SMesh sm;
	CGAL::convex_hull_3(pts.begin(), pts.end(), sm, HullTraits());
	if (sm.number_of_faces() < 4 || !CGAL::is_triangle_mesh(sm))
		throw Error(Error::InvalidInput, "The points are coplanar: the shape encloses no volume.");
	return sm;
}

// A facet grows from its largest triangle, across edges, over the proper triangles whose corners lie
// within noise of that first triangle's plane. Judged against one plane, not neighbour against
// neighbour: a small triangle's normal is known only to noise / its height, so pairwise it would join
// planes that differ by far more than rounding (a CAD face flat to a few ulps of single precision is a
// fan of such planes), and whether such a triangle exists at all hangs on rounding.
void grow_facets(const std::vector<Vec3>& points, const std::vector<Tri>& triangles,
                 const std::vector<std::vector<std::pair<double, int>>>& across, const std::vector<char>& proper,
                 const std::vector<Vec3>& normal, const std::vector<double>& height, double noise, DisjointSets& sets)
{
	std::vector<int> seeds;
	for (int t = 0; t < (int) triangles.size(); ++t)
		if (proper[t]) seeds.push_back(t);
	const auto twice_area = [&](int t) { return height[t] * across[t][0].first; };
	std::stable_sort(seeds.begin(), seeds.end(), [&](int a, int b) { return twice_area(a) > twice_area(b); });
	std::vector<char> taken(triangles.size(), 0);
	std::vector<int>  todo;
	for (int seed : seeds) {
		if (taken[seed]) continue;
		taken[seed]     = 1;
		const Vec3   n  = normal[seed];
		const double d  = n.dot(points[triangles[seed][0]]);
		auto         on = [&](int g) {
			for (int v : triangles[g])
				if (std::abs(n.dot(points[v]) - d) > noise) return false;
			return true;
		};
		todo.assign(1, seed);
		while (!todo.empty()) {
			const int t = todo.back();
			todo.pop_back();
			for (const auto& [len, g] : across[t])
				if (proper[g] && !taken[g] && on(g)) taken[g] = 1, sets.unite(g, seed), todo.push_back(g);
		}
	}
}

// Coplanar neighbouring triangles merged into groups (union-find roots per triangle). "Coplanar" to
// rounding, not exactly: a cut's cap is planar only up to the rounding of its crossing points, and
// which way that rounding falls depends on the pose, so an exact test would split the same cap into
// different facets (and spurious bridges) when the object is rotated. A facet takes the triangles
// whose corners lie within noise of its largest triangle's plane (noise: 1e-12 of the extent, generous
// for coordinates of unit size). `across[t]`: (edge length, neighbouring triangle) over t's edges.
std::vector<int> coplanar_groups(const std::vector<Vec3>& points, const std::vector<Tri>& triangles,
                                 std::vector<std::vector<std::pair<double, int>>>& across)
{
	double reach = 0;   // from the first point: a size for the tolerances
	for (const Vec3& p : points) reach = std::max(reach, (p - points[0]).norm());
	const double noise = 1e-12 * reach;
	// A sliver (nearly collinear corners, as cut outlines give) has no normal of its own worth the
	// name: it joins a proper neighbouring facet afterwards, whose plane holds it to rounding (across
	// its longest edge when that neighbour is proper; slivers next to slivers wait for a later pass).
	// Merging slivers by their normals would chain unrelated facets together.
	std::vector<char>   proper(triangles.size(), 1);
	std::vector<double> height(triangles.size());
	std::vector<Vec3>   normal(triangles.size());
	for (int t = 0; t < (int) triangles.size(); ++t) {
		std::sort(across[t].rbegin(), across[t].rend());
		const Tri& T = triangles[t];
		const Vec3 n = (points[T[1]] - points[T[0]]).cross(points[T[2]] - points[T[0]]);
		height[t]    = n.norm() / across[t][0].first;
		normal[t]    = n.normalized();
		proper[t]    = height[t] > 1e-10 * reach;
	}
	DisjointSets sets(triangles.size());
	grow_facets(points, triangles, across, proper, normal, height, noise, sets);
	for (bool changed = true; changed;) {
		changed = false;
		for (int t = 0; t < (int) triangles.size(); ++t) {
			if (proper[t]) continue;
			for (const auto& [len, g] : across[t])
				if (proper[g]) {
					sets.unite(t, g);
					proper[t] = changed = true;
					break;
				}
		}
	}
	std::vector<int> group(triangles.size());
	for (int t = 0; t < (int) triangles.size(); ++t) group[t] = sets.root(t);
	return group;
}

} // namespace

// CGAL's hull is read in an order that depends on the points alone: vertices sorted, each triangle from
// its least vertex, triangles sorted. CGAL hands its faces out in an order that follows allocation (it
// differs between runs and threads), and the facet grouping below breaks ties by order.
ConvexHull::ConvexHull(const std::vector<Vec3>& input)
{
	std::unordered_map<Point, int, BitsHash> index;   // first input index of each distinct point
	const SMesh                              sm = cgal_hull(input, index);
	std::vector<SMesh::Vertex_index>         vs(sm.vertices().begin(), sm.vertices().end());
	std::sort(vs.begin(), vs.end(), [&](SMesh::Vertex_index a, SMesh::Vertex_index b) {
		return std::make_tuple(sm.point(a).x(), sm.point(a).y(), sm.point(a).z()) <
		       std::make_tuple(sm.point(b).x(), sm.point(b).y(), sm.point(b).z());
	});
	std::vector<int> rank(sm.number_of_vertices());
	for (SMesh::Vertex_index v : vs) {
		rank[v.idx()] = (int) points.size();
		points.push_back(to_vec(sm.point(v)));
		point_source.push_back(index.at(sm.point(v)));
	}
	for (auto f : sm.faces()) {
		Tri t;
		int k = 0;
		for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) t[k++] = rank[v.idx()];
		std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
		triangles.push_back(t);
	}
	std::sort(triangles.begin(), triangles.end());
	// Each directed edge (a, b) -> its triangle; the neighbour across (a, b) holds (b, a).
	std::vector<std::pair<uint64_t, int>> edge;
	edge.reserve(3 * triangles.size());
	auto key = [](int a, int b) { return (uint64_t) a << 32 | (uint32_t) b; };
	for (int t = 0; t < (int) triangles.size(); ++t)
		for (int i = 0; i < 3; ++i) edge.emplace_back(key(triangles[t][i], triangles[t][(i + 1) % 3]), t);
	std::sort(edge.begin(), edge.end());
	std::vector<std::vector<std::pair<double, int>>> across(triangles.size());   // (edge length, face)
	for (int t = 0; t < (int) triangles.size(); ++t)
		for (int i = 0; i < 3; ++i) {
			const int a = triangles[t][i], b = triangles[t][(i + 1) % 3];
			const auto it = std::lower_bound(edge.begin(), edge.end(), std::make_pair(key(b, a), -1));
			across[t].emplace_back((points[b] - points[a]).norm(), it->second);
		}
	index_facets(coplanar_groups(points, triangles, across));
	index_corners();
	tree_ = std::make_unique<Tree>();
	for (const Tri& t : triangles)
		tree_->tris.emplace_back(to_cgal(points[t[0]]), to_cgal(points[t[1]]), to_cgal(points[t[2]]));
	tree_->aabb.insert(tree_->tris.cbegin(), tree_->tris.cend());
	tree_->aabb.accelerate_distance_queries();
}

// Facets numbered in order of their first triangle; their planes (area-weighted normal, through the
// centroid of their corners) and areas; the hull's volume.
void ConvexHull::index_facets(const std::vector<int>& group)
{
	std::unordered_map<int, int> facet_id;
	triangle_facet.resize(triangles.size());
	for (int t = 0; t < (int) triangles.size(); ++t) {
		auto [it, fresh] = facet_id.emplace(group[t], (int) facet_id.size());
		if (fresh) facet_triangles.emplace_back();
		triangle_facet[t] = it->second;
		facet_triangles[it->second].push_back(t);
	}
	facet_plane.resize(facet_triangles.size());
	facet_area.assign(facet_triangles.size(), 0.0);
	for (int f = 0; f < (int) facet_triangles.size(); ++f) {
		Vec3 n = Vec3::Zero();
		Vec3 c = Vec3::Zero();
		for (int t : facet_triangles[f]) {
			const Vec3 &a = points[triangles[t][0]], &b = points[triangles[t][1]], &d = points[triangles[t][2]];
			Vec3 tn = (b - a).cross(d - a);
			n += tn;
			c += a + b + d;
			facet_area[f] += 0.5 * tn.norm();
		}
		c /= 3.0 * facet_triangles[f].size();
		facet_plane[f].n = n.normalized();
		facet_plane[f].d = facet_plane[f].n.dot(c);
	}
	volume = signed_volume(TriMesh{points, triangles});
}

// Each hull vertex's triangles (CSR), and one of them.
void ConvexHull::index_corners()
{
	point_triangle.assign(points.size(), -1);
	corner_start_.assign(points.size() + 1, 0);
	for (int t = 0; t < (int) triangles.size(); ++t)
		for (int v : triangles[t]) {
			point_triangle[v] = t;
			++corner_start_[v + 1];
		}
	for (size_t v = 0; v < points.size(); ++v) corner_start_[v + 1] += corner_start_[v];
	corner_tris_.resize(corner_start_.back());
	std::vector<int> fill(corner_start_.begin(), corner_start_.end() - 1);
	for (int t = 0; t < (int) triangles.size(); ++t)
		for (int v : triangles[t]) corner_tris_[fill[v]++] = t;
}

double ConvexHull::distance_to_boundary(const Vec3& p, int* triangle, int near, Vec3* closest) const
{
	const Point q = to_cgal(p);
	auto        hit = near < 0 ? tree_->aabb.closest_point_and_primitive(q)
	                           : tree_->aabb.closest_point_and_primitive(
	                                 q, std::make_pair(K().construct_projected_point_3_object()(tree_->tris[near], q),
	                                                   tree_->tris.cbegin() + near));
	if (triangle) *triangle = (int) (hit.second - tree_->tris.cbegin());
	if (closest) *closest = Vec3(hit.first.x(), hit.first.y(), hit.first.z());
	return std::sqrt(CGAL::squared_distance(hit.first, q));
}

double ConvexHull::distance_to_facet(const Vec3& p, int facet) const
{
	// The facet's triangles tile a convex polygon: once one holds p's projection, the plane
	// distance is the answer.
	const double plane2 = std::pow(facet_plane[facet].eval(p), 2) * (1 + 1e-12);
	const Point  q      = to_cgal(p);
	double       d2     = std::numeric_limits<double>::infinity();
	for (int t : facet_triangles[facet]) {
		d2 = std::min(d2, CGAL::squared_distance(q, tree_->tris[t]));
		if (d2 <= plane2) break;
	}
	return std::sqrt(d2);
}

int ConvexHull::facet_facing(int t, const Vec3& n) const
{
	int    best  = triangle_facet[t];
	double align = facet_plane[best].n.dot(n);
	for (int v : triangles[t])
		for (int i = corner_start_[v]; i < corner_start_[v + 1]; ++i) {
			const int f = triangle_facet[corner_tris_[i]];
			if (facet_plane[f].n.dot(n) > align) align = facet_plane[f].n.dot(n), best = f;
		}
	return best;
}

TriMesh ConvexHull::mesh() const
{
	return TriMesh{points, triangles};
}

} // namespace acd
