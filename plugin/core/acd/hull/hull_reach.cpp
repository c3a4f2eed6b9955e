#include "acd/hull/hull_reach.h"

#include <CGAL/AABB_traits_3.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive_3.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>
#include <queue>

namespace acd {

namespace {

using K         = CGAL::Simple_cartesian<double>;
using Triangle  = K::Triangle_3;
using TriVec    = std::vector<Triangle>;
using Primitive = CGAL::AABB_triangle_primitive_3<K, TriVec::const_iterator>;
using AABB      = CGAL::AABB_tree<CGAL::AABB_traits_3<K, Primitive>>;

K::Point_3 to_cgal(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

// Distance queries to the part's surface, built only when some triangle needs one.
class SurfaceDistance
{
public:
	explicit SurfaceDistance(const TriMesh& m)
	{
		tris_.reserve(m.F.size());
		for (const Tri& t : m.F) tris_.emplace_back(to_cgal(m.V[t[0]]), to_cgal(m.V[t[1]]), to_cgal(m.V[t[2]]));
		tree_.insert(tris_.cbegin(), tris_.cend());
		tree_.accelerate_distance_queries();
	}
	// Distance from p to the surface; `nearest` gets the closest point, `face` the face holding it.
	double operator()(const Vec3& p, Vec3* nearest, int* face) const
	{
		const K::Point_3 q   = to_cgal(p);
		const auto       hit = tree_.closest_point_and_primitive(q);
		if (nearest) *nearest = Vec3(hit.first.x(), hit.first.y(), hit.first.z());
		if (face) *face = (int) (hit.second - tris_.cbegin());
		return std::sqrt(CGAL::squared_distance(q, hit.first));
	}
	double to_face(const Vec3& p, int face) const { return std::sqrt(CGAL::squared_distance(to_cgal(p), tris_[face])); }

private:
	TriVec tris_;
	AABB   tree_;
};

struct Piece
{
	Vec3   a, b, c;
	double d = 0;       // the centre's distance to the surface
	double bound = 0;   // no point of the piece lies farther from the surface
	int    facet = -1;
	bool   operator<(const Piece& o) const { return bound < o.bound; }
};

} // namespace

HullReach hull_reach(const TriMesh& m, const ConvexHull& hull, const std::vector<char>& bridge, double floor,
                     double slack, double relative, int max_evaluations)
{
	HullReach out;
	// Hull vertices are surface vertices, so a point of a hull triangle is no farther from the
	// surface than from its nearest corner: at most the longest edge / sqrt(3). Triangles that this
	// already settles need no query (most of them, on a fine mesh).
	std::vector<int> open;
	for (int t = 0; t < (int) hull.triangles.size(); ++t) {
		if (!bridge[hull.triangle_facet[t]]) continue;
		const Tri& T = hull.triangles[t];
		const double longest = std::max({(hull.points[T[0]] - hull.points[T[1]]).norm(),
		                                 (hull.points[T[1]] - hull.points[T[2]]).norm(),
		                                 (hull.points[T[2]] - hull.points[T[0]]).norm()});
		if (longest / std::sqrt(3.0) > floor + slack) open.push_back(t);
		else out.upper = std::max(out.upper, longest / std::sqrt(3.0));
	}
	if (open.empty()) return out;

	const SurfaceDistance              dist(m);
	std::priority_queue<Piece>         heap;
	// Two bounds: the centre's distance plus the corners' distance to the centre (Lipschitz); and the
	// distance to the face nearest the centre, which is convex over the piece, so at most its value at
	// a corner. The second is what settles a flat lid above a flat floor without splitting it up.
	auto push = [&](const Vec3& a, const Vec3& b, const Vec3& c, int facet) {
		Piece      p{a, b, c};
		const Vec3 centre = (a + b + c) / 3.0;
		p.facet           = facet;
		Vec3 near;
		int  face = -1;
		p.d       = dist(centre, &near, &face);
		++out.evaluations;
		const double lipschitz = p.d + std::max({(a - centre).norm(), (b - centre).norm(), (c - centre).norm()});
		const double convex    = std::max({dist.to_face(a, face), dist.to_face(b, face), dist.to_face(c, face)});
		p.bound                = std::min(lipschitz, convex);
		if (p.d > out.lower) {
			out.lower   = p.d;
			out.witness = centre;
			out.nearest = near;
			out.facet   = facet;
		}
		heap.push(p);
	};
	for (int t : open) {
		const Tri& T = hull.triangles[t];
		push(hull.points[T[0]], hull.points[T[1]], hull.points[T[2]], hull.triangle_facet[t]);
	}
	while (!heap.empty()) {
		const Piece p = heap.top();
		// Until a point beyond floor + slack is found, every bound is settled against floor + slack, so
		// that whether the reach is certified there does not hang on which point the search met first.
		const double bar = out.lower > floor + slack ? out.lower * (1 + relative) + slack : floor + slack;
		if (p.bound <= bar || out.evaluations >= max_evaluations) break;
		heap.pop();
		const Vec3 ab = (p.a + p.b) / 2, bc = (p.b + p.c) / 2, ca = (p.c + p.a) / 2;
		push(p.a, ab, ca, p.facet);
		push(ab, p.b, bc, p.facet);
		push(ca, bc, p.c, p.facet);
		push(ab, bc, ca, p.facet);
	}
	if (!heap.empty()) out.upper = std::max(out.upper, heap.top().bound);
	out.upper = std::max(out.upper, out.lower);
	return out;
}

} // namespace acd
