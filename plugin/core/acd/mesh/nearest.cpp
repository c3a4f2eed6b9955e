#include "acd/mesh/nearest.h"
#include "acd/mesh/parallel.h"

#include <CGAL/AABB_traits_3.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>

namespace acd {

namespace {
using K         = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangles = std::vector<K::Triangle_3>;
using AABB      = CGAL::AABB_tree<CGAL::AABB_traits_3<K, CGAL::AABB_triangle_primitive_3<K, Triangles::const_iterator>>>;
K::Point_3 point(const Vec3& v) { return K::Point_3(v.x(), v.y(), v.z()); }
} // namespace

struct NearestOnSurface::Tree
{
	Triangles tris;
	AABB      aabb;
};

NearestOnSurface::NearestOnSurface(const TriMesh& s) : tree(std::make_unique<Tree>())
{
	for (const Tri& t : s.F)
		if (finite_face(s, t)) tree->tris.emplace_back(point(s.V[t[0]]), point(s.V[t[1]]), point(s.V[t[2]]));
	tree->aabb.insert(tree->tris.begin(), tree->tris.end());
	tree->aabb.build();
	if (tree->tris.empty()) return;
	tree->aabb.accelerate_distance_queries();
	tree->aabb.closest_point(point(s.V[s.F[0][0]]));   // builds what queries share before they run in parallel
}

NearestOnSurface::~NearestOnSurface() = default;

Vec3 NearestOnSurface::closest(const Vec3& q) const
{
	if (tree->tris.empty()) return Vec3::Constant(INFINITY);
	const K::Point_3 p = tree->aabb.closest_point(point(q));
	return Vec3(p.x(), p.y(), p.z());
}

double NearestOnSurface::distance(const Vec3& q) const
{
	if (tree->tris.empty()) return INFINITY;
	return std::sqrt(tree->aabb.squared_distance(point(q)));
}

double NearestOnSurface::farthest(const std::vector<Vec3>& points, size_t samples) const
{
	if (points.empty()) return 0;
	const size_t        step = std::max<size_t>(1, points.size() / std::max<size_t>(1, samples));
	const size_t        n    = (points.size() + step - 1) / step;
	std::vector<double> d(n, 0);
	parallel_for_chunked(n, 4096, [&](size_t i) { d[i] = distance(points[i * step]); });
	return *std::max_element(d.begin(), d.end());
}

double NearestOnSurface::farthest_on(const TriMesh& other) const
{
	if (other.F.empty()) return 0;
	std::vector<double> corner(other.V.size(), 0), d(other.F.size(), 0);
	std::vector<char>   used(other.V.size(), 0);
	for (const Tri& t : other.F)
		if (finite_face(other, t)) used[t[0]] = used[t[1]] = used[t[2]] = 1;
	parallel_for_chunked(other.V.size(), 4096, [&](size_t v) { corner[v] = used[v] ? distance(other.V[v]) : 0; });
	const double corners = *std::max_element(corner.begin(), corner.end());
	parallel_for_chunked(other.F.size(), 1024, [&](size_t f) {
		const Tri& t = other.F[f];
		if (!finite_face(other, t)) return;
		const Vec3 &a = other.V[t[0]], &b = other.V[t[1]], &c = other.V[t[2]];
		d[f] = std::max({corner[t[0]], corner[t[1]], corner[t[2]]});
		// The distance is 1-Lipschitz: no point of the face lies farther than its farthest corner plus
		// its longest edge / sqrt(3), so a face within the corners' maximum that way adds nothing.
		if (d[f] + std::max({(a - b).norm(), (b - c).norm(), (c - a).norm()}) / std::sqrt(3.0) <= corners) return;
		for (const Vec3& p : {Vec3((a + b) / 2), Vec3((b + c) / 2), Vec3((c + a) / 2), Vec3((a + b + c) / 3)})
			d[f] = std::max(d[f], distance(p));
	});
	return d.empty() ? 0.0 : *std::max_element(d.begin(), d.end());
}

} // namespace acd
