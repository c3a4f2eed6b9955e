#include "acd/glue.h"
#include "rims.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/centroid.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace acd {

namespace {

// The 2D work is exact: every triangle of the seam's triangulation is then wholly inside or outside
// each face, however shallow the crossings of the two sides' edges.
using K     = CGAL::Exact_predicates_exact_constructions_kernel;
using P2    = K::Point_2;

// The seam's 2D triangulation: the two sides' faces on a plane, every edge a constraint, crossings
// exact; each triangle lies wholly inside or outside each face, so one point decides which cover it.
struct Where
{
	int v = -1;   // the solid's vertex there (-1: a crossing of the two sides' edges)
};
using Vb  = CGAL::Triangulation_vertex_base_with_info_2<Where, K>;
using Fb  = CGAL::Constrained_triangulation_face_base_2<K>;
using TDS = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, TDS, CGAL::Exact_intersections_tag>;

struct Face
{
	Tri  t;
	int  from = 0;       // 0: a, 1: b
	bool dropped = false;
};

// The solids' faces on one plane replaced by the region exactly one of them covers (the two sides'
// opposite faces cancel where they overlap), triangulated so that no seam vertex hangs on an edge.
class PlaneSeam
{
public:
	PlaneSeam(std::vector<Vec3>& V, const Plane& pl, double eps) : V(V), pl(pl), eps(eps)
	{
		u = pl.n.unitOrthogonal();
		w = pl.n.cross(u);
	}

	// Vertices that coincide in the plane (within eps) with another are added to `alias`, renamed to
	// it; they are rounding-error copies of one point the two sides computed apart.
	void cut(std::vector<Face>& faces, std::map<int, int>& alias)
	{
		std::vector<int> on;
		bool             side[2] = {false, false};
		for (int f = 0; f < (int) faces.size(); ++f)
			if (!faces[f].dropped && pl.holds(V, faces[f].t, eps)) on.push_back(f), side[faces[f].from] = true;
		if (!side[0] || !side[1]) return;
		std::vector<int> vs;
		for (int f : on)
			for (int v : faces[f].t) vs.push_back(v);
		std::sort(vs.begin(), vs.end());
		vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
		for (int v : vs) flat.push_back({Eigen::Vector2d(u.dot(V[v]), w.dot(V[v])), v});
		std::sort(flat.begin(), flat.end(), [](const auto& p, const auto& q) { return p.first.x() < q.first.x(); });
		for (size_t i = 0; i < flat.size(); ++i)
			for (size_t j = i + 1; j < flat.size() && flat[j].first.x() - flat[i].first.x() <= eps; ++j)
				if ((flat[j].first - flat[i].first).norm() <= eps) {
					const int p = root(flat[i].second, alias), q = root(flat[j].second, alias);
					if (p != q) alias[std::max(p, q)] = std::min(p, q);
				}
		CDT                                  cdt;
		std::map<int, CDT::Vertex_handle>    at;
		std::vector<std::array<P2, 3>>       tri;
		std::vector<Eigen::AlignedBox2d>     box;
		for (int f : on) {
			std::array<P2, 3> q;
			for (int k = 0; k < 3; ++k) {
				const int v = root(faces[f].t[k], alias);
				auto [it, fresh] = at.emplace(v, CDT::Vertex_handle());
				if (fresh) {
					it->second = cdt.insert(P2(u.dot(V[v]), w.dot(V[v])));
					if (it->second->info().v < 0) it->second->info().v = v;
					else if (it->second->info().v != v) alias[v] = it->second->info().v;
				}
				q[k] = it->second->point();
			}
			tri.push_back(q);
			box.push_back(bounds(q));
		}
		for (int f : on)
			for (int k = 0; k < 3; ++k) {
				const auto p = at[root(faces[f].t[k], alias)], q = at[root(faces[f].t[(k + 1) % 3], alias)];
				if (p != q) cdt.insert_constraint(p, q);
			}
		std::vector<Face> kept;
		for (auto fh : cdt.finite_face_handles()) {
			const P2 c = CGAL::centroid(fh->vertex(0)->point(), fh->vertex(1)->point(), fh->vertex(2)->point());
			const Eigen::Vector2d cd(CGAL::to_double(c.x()), CGAL::to_double(c.y()));
			int cover = -1, covers = 0;
			for (size_t i = 0; i < on.size() && covers < 2; ++i)
				if (box[i].exteriorDistance(cd) <= 1e-9 * (1 + box[i].diagonal().norm()) && inside(tri[i], c)) cover = (int) i, ++covers;
			if (covers != 1) continue;
			Face f;
			f.from = faces[on[cover]].from;
			const bool turned = CGAL::orientation(tri[cover][0], tri[cover][1], tri[cover][2]) == CGAL::CLOCKWISE;
			for (int k = 0; k < 3; ++k) f.t[turned ? 2 - k : k] = vertex(fh->vertex(k), alias);
			if (!needle(f.t)) kept.push_back(f);
		}
		for (int f : on) faces[f].dropped = true;
		faces.insert(faces.end(), kept.begin(), kept.end());
	}

private:
	std::vector<Vec3>& V;
	const Plane        pl;
	const double       eps;
	Vec3               u, w;

	// A sliver of the seam no wider than eps once rounded (its corners on one line, or snapped
	// together): dropped, its long edge's neighbour gets its middle corner (close_rims).
	bool needle(const Tri& t) const
	{
		if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return true;
		double longest = 0;
		for (int k = 0; k < 3; ++k) longest = std::max(longest, (V[t[(k + 1) % 3]] - V[t[k]]).norm());
		return (V[t[1]] - V[t[0]]).cross(V[t[2]] - V[t[0]]).norm() <= eps * longest;
	}

	static Eigen::AlignedBox2d bounds(const std::array<P2, 3>& q)
	{
		Eigen::AlignedBox2d b;
		for (const P2& p : q) b.extend(Eigen::Vector2d(CGAL::to_double(p.x()), CGAL::to_double(p.y())));
		return b;
	}

	static bool inside(const std::array<P2, 3>& t, const P2& c)
	{
		const CGAL::Orientation o = CGAL::orientation(t[0], t[1], t[2]);
		return o != CGAL::COLLINEAR && CGAL::orientation(t[0], t[1], c) == o && CGAL::orientation(t[1], t[2], c) == o &&
		       CGAL::orientation(t[2], t[0], c) == o;
	}

	std::vector<std::pair<Eigen::Vector2d, int>> flat;   // the plane's vertices in 2D, by x

	static int root(int v, const std::map<int, int>& alias)
	{
		for (auto it = alias.find(v); it != alias.end(); it = alias.find(v)) v = it->second;
		return v;
	}

	// The solid's vertex, or a crossing: the solid's vertex within eps of it, else a new vertex lifted
	// onto the plane (made once).
	int vertex(CDT::Vertex_handle vh, const std::map<int, int>& alias)
	{
		if (vh->info().v < 0) {
			const Eigen::Vector2d p(CGAL::to_double(vh->point().x()), CGAL::to_double(vh->point().y()));
			const auto lo = std::lower_bound(flat.begin(), flat.end(), p.x() - eps, [](const auto& q, double x) { return q.first.x() < x; });
			for (auto it = lo; it != flat.end() && it->first.x() <= p.x() + eps && vh->info().v < 0; ++it)
				if ((it->first - p).norm() <= eps) vh->info().v = root(it->second, alias);
			if (vh->info().v < 0) {
				V.push_back(pl.n * pl.d + p.x() * u + p.y() * w);
				vh->info().v = (int) V.size() - 1;
			}
		}
		return vh->info().v;
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
	std::map<int, int> alias;
	for (const Plane& pl : planes) PlaneSeam(V, pl, eps).cut(faces, alias);
	TriMesh all;
	all.V = std::move(V);
	for (const Face& f : faces) {
		if (f.dropped) continue;
		Tri t = f.t;
		for (int& v : t)
			while (alias.count(v)) v = alias[v];
		if (t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) all.F.push_back(t);
	}
	close_rims(all, eps);
	return without_needles(compacted(all));
}

} // namespace acd
