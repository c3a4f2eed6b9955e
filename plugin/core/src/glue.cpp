#include "acd/glue.h"
#include "rims.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace acd {

namespace {

// The 2D work is exact: a crossing of the two sides' edges is then the same point whichever side
// computes it (rounded once, it is the same double), however shallow the crossing.
using K     = CGAL::Exact_predicates_exact_constructions_kernel;
using P2    = K::Point_2;
using Poly2 = std::vector<P2>;   // convex, counter-clockwise

// The part of convex q to the left of the line a -> b (or to its right).
Poly2 clip(const Poly2& q, const P2& a, const P2& b, bool left)
{
	Poly2      out;
	const auto side = [&](const P2& p) {
		const CGAL::Orientation o = CGAL::orientation(a, b, p);
		return left ? int(o) : -int(o);
	};
	for (size_t i = 0; i < q.size(); ++i) {
		const P2 &c = q[i], &n = q[(i + 1) % q.size()];
		const int sc = side(c), sn = side(n);
		if (sc >= 0) out.push_back(c);
		if (sc * sn < 0) {
			const auto x = CGAL::intersection(K::Line_2(a, b), K::Segment_2(c, n));
			if (const P2* p = x ? std::get_if<P2>(&*x) : nullptr) out.push_back(*p);
		}
	}
	return out;
}

// The area, exact (signed): a piece the clipping pinched to nothing has none.
K::FT exact_area(const Poly2& q)
{
	K::FT a = 0;
	for (size_t i = 1; i + 1 < q.size(); ++i) a += CGAL::area(q[0], q[i], q[i + 1]);
	return a;
}

// Area, rounded (only its sign is used: the orientation a face had).
double area(const Poly2& q)
{
	double a = 0;
	for (size_t i = 0; i < q.size(); ++i) {
		const P2 &p = q[i], &r = q[(i + 1) % q.size()];
		a += CGAL::to_double(p.x()) * CGAL::to_double(r.y()) - CGAL::to_double(p.y()) * CGAL::to_double(r.x());
	}
	return a / 2;
}


// q minus triangle s (counter-clockwise): the parts of q outside each of s's edges in turn.
std::vector<Poly2> minus(const Poly2& q, const Poly2& s)
{
	std::vector<Poly2> out;
	Poly2              in = q;
	for (int k = 0; k < 3 && in.size() >= 3; ++k) {
		const P2 &a = s[k], &b = s[(k + 1) % 3];
		Poly2     outside = clip(in, a, b, false);
		if (outside.size() >= 3) out.push_back(std::move(outside));
		in = clip(in, a, b, true);
	}
	return out;
}

bool boxes_meet(const Poly2& a, const Poly2& b)
{
	Eigen::AlignedBox2d A, B;
	for (const P2& p : a) A.extend(Eigen::Vector2d(CGAL::to_double(p.x()), CGAL::to_double(p.y())));
	for (const P2& p : b) B.extend(Eigen::Vector2d(CGAL::to_double(p.x()), CGAL::to_double(p.y())));
	return A.intersects(B);
}

struct Face
{
	Tri  t;
	int  from = 0;       // 0: a, 1: b
	bool dropped = false;
};

// The solids' faces on one plane, cut against each other.
class PlaneSeam
{
public:
	PlaneSeam(std::vector<Vec3>& V, const Plane& pl, double eps) : V(V), pl(pl), eps(eps)
	{
		u = pl.n.unitOrthogonal();
		w = pl.n.cross(u);
	}

	void cut(std::vector<Face>& faces)
	{
		std::vector<int> on[2];
		for (int f = 0; f < (int) faces.size(); ++f)
			if (!faces[f].dropped && pl.holds(V, faces[f].t, eps)) on[faces[f].from].push_back(f);
		if (on[0].empty() || on[1].empty()) return;
		std::map<int, Poly2> tri;   // each face on the plane in 2D, as it is oriented
		for (int s = 0; s < 2; ++s)
			for (int f : on[s]) tri[f] = flat(faces[f].t);
		std::vector<Face> added;
		for (int s = 0; s < 2; ++s)
			for (int f : on[s]) {
				std::vector<int> others;
				for (int g : on[1 - s])
					if (facing(faces[f].t) != facing(faces[g].t) && boxes_meet(tri[f], tri[g])) others.push_back(g);
				if (others.empty()) continue;
				std::vector<Poly2> left{ccw(tri[f])};
				for (int g : others) {
					const Poly2        covered = ccw(tri[g]);
					std::vector<Poly2> next;
					for (const Poly2& q : left)
						for (Poly2& r : boxes_meet(q, covered) ? minus(q, covered) : std::vector<Poly2>{q})
							if (exact_area(r) > 0) next.push_back(std::move(r));
					left.swap(next);
				}
				const bool turned = area(tri[f]) < 0;
				for (const Poly2& q : left) fan(q, turned, faces[f].from, added);
				faces[f].dropped = true;
			}
		for (Face& f : added) faces.push_back(f);
	}

private:
	std::vector<Vec3>&              V;
	const Plane                     pl;
	const double                    eps;
	Vec3                            u, w;
	std::map<std::pair<double, double>, int> at;   // plane points made so far, by their 2D position

	bool facing(const Tri& t) const { return pl.n.dot((V[t[1]] - V[t[0]]).cross(V[t[2]] - V[t[0]])) > 0; }

	Poly2 flat(const Tri& t)
	{
		Poly2 q;
		for (int v : t) {
			const double x = u.dot(V[v]), y = w.dot(V[v]);
			at.emplace(std::make_pair(x, y), v);
			q.emplace_back(x, y);
		}
		return q;
	}

	static Poly2 ccw(Poly2 q)
	{
		if (area(q) < 0) std::reverse(q.begin(), q.end());
		return q;
	}

	// The vertex at 2D point p: a vertex of the solids there (the same doubles, or within eps), or a
	// new one lifted onto the plane.
	int vertex(const P2& e)
	{
		const double x = CGAL::to_double(CGAL::exact(e.x())), y = CGAL::to_double(CGAL::exact(e.y()));
		const auto   it = at.find({x, y});
		if (it != at.end()) return it->second;
		for (const auto& [q, v] : at)
			if (std::hypot(q.first - x, q.second - y) <= eps) return v;
		V.push_back(pl.n * pl.d + x * u + y * w);
		at.emplace(std::make_pair(x, y), (int) V.size() - 1);
		return (int) V.size() - 1;
	}

	void fan(const Poly2& q, bool turned, int from, std::vector<Face>& out)
	{
		std::vector<int> id;
		for (const P2& p : q) {
			const int v = vertex(p);
			if (id.empty() || (v != id.back() && v != id.front())) id.push_back(v);
		}
		for (size_t k = 1; k + 1 < id.size(); ++k) {
			if (id[k] == id[0] || id[k + 1] == id[0] || id[k] == id[k + 1]) continue;   // a pinched sliver
			Face f;
			f.t    = turned ? Tri{id[0], id[k + 1], id[k]} : Tri{id[0], id[k], id[k + 1]};
			f.from = from;
			out.push_back(f);
		}
	}
};

// Slivers of the two sides' seams a rounding error wide are kept by the exact clipping and collapse
// to zero area once rounded: CGAL's repair (exact predicates) collapses or flips them away.
TriMesh without_needles(const TriMesh& m)
{
	using IK = CGAL::Exact_predicates_inexact_constructions_kernel;
	using SM = CGAL::Surface_mesh<IK::Point_3>;
	SM                           sm;
	std::vector<SM::Vertex_index> id;
	for (const Vec3& p : m.V) id.push_back(sm.add_vertex(IK::Point_3(p.x(), p.y(), p.z())));
	for (const Tri& t : m.F)
		if (sm.add_face(id[t[0]], id[t[1]], id[t[2]]) == SM::null_face()) return m;   // not a manifold surface
	CGAL::Polygon_mesh_processing::remove_degenerate_faces(sm);
	sm.collect_garbage();
	TriMesh out;
	for (auto v : sm.vertices()) out.V.emplace_back(sm.point(v).x(), sm.point(v).y(), sm.point(v).z());
	for (auto f : sm.faces()) {
		Tri t;
		int k = 0;
		for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) t[std::min(k++, 2)] = (int) v;
		if (k == 3) out.F.push_back(t);
	}
	return out;
}

} // namespace

TriMesh glue(const TriMesh& a, const TriMesh& b, const std::vector<Plane>& planes, double eps)
{
	std::vector<Vec3> V;
	ExactWeld         weld(V);
	std::vector<Face> faces;
	for (int s = 0; s < 2; ++s) {
		const TriMesh&         m  = s ? b : a;
		const std::vector<int> id = weld.add(m);
		for (const Tri& t : m.F) faces.push_back({{id[t[0]], id[t[1]], id[t[2]]}, s, false});
	}
	for (const Plane& pl : planes) PlaneSeam(V, pl, eps).cut(faces);
	TriMesh all;
	all.V = std::move(V);
	for (const Face& f : faces)
		if (!f.dropped) all.F.push_back(f.t);
	close_rims(all, eps);
	return without_needles(compacted(all));
}

} // namespace acd
