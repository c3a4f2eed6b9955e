#include "acd/solid/glue.h"
#include "acd/solid/rims.h"
#include "acd/mesh/measures.h"
#include "acd/mesh/weld.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/centroid.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

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
// The "plus" hierarchy names the input edges each triangulation edge lies on (its side's boundary).
using CDT = CGAL::Constrained_triangulation_plus_2<CGAL::Constrained_Delaunay_triangulation_2<K, TDS, CGAL::Exact_intersections_tag>>;

// A plane vertex's name once the copies within eps of it are one (`alias`: copy -> kept vertex).
int renamed(int v, const std::map<int, int>& alias)
{
	for (auto it = alias.find(v); it != alias.end(); it = alias.find(v)) v = it->second;
	return v;
}

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
	PlaneSeam(std::vector<Vec3>& V, const Plane& pl, double eps, std::map<int, int>& alias)
	    : V(V), pl(pl), eps(eps), alias(alias)
	{
		u = pl.n.unitOrthogonal();
		w = pl.n.cross(u);
	}

	// Vertices that coincide in the plane (within eps) with another are added to `alias`, renamed to
	// it: rounding-error copies of one point the two sides computed apart.
	void cut(std::vector<Face>& faces)
	{
		const std::vector<int> on = faces_on(faces);
		if (on.empty()) return;
		snap(on, faces);
		insert_corners(on, faces);
		std::vector<Face> kept;
		if (!by_boundaries(on, faces, kept)) {
			constrain_edges();
			kept = covered_once(on, faces);
		}
		for (int f : on) faces[f].dropped = true;
		faces.insert(faces.end(), kept.begin(), kept.end());
	}

private:
	using Corners = std::array<CDT::Vertex_handle, 3>;

	std::vector<Vec3>&                           V;
	const Plane                                  pl;
	const double                                 eps;
	std::map<int, int>&                          alias;
	Vec3                                         u, w;
	std::vector<std::pair<Eigen::Vector2d, int>> flat;   // the plane's vertices in 2D, by x
	CDT                                          cdt;
	std::vector<Corners>                         corners;   // each face on the plane in the triangulation

	// The faces on the plane, if both solids have some there.
	std::vector<int> faces_on(const std::vector<Face>& faces) const
	{
		std::vector<int> on;
		bool             side[2] = {false, false};
		for (int f = 0; f < (int) faces.size(); ++f)
			if (!faces[f].dropped && pl.holds(V, faces[f].t, eps)) on.push_back(f), side[faces[f].from] = true;
		return side[0] && side[1] ? on : std::vector<int>{};
	}

	// The plane's vertices within eps of each other become one (the lowest index).
	void snap(const std::vector<int>& on, const std::vector<Face>& faces)
	{
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
					const int p = root(flat[i].second), q = root(flat[j].second);
					if (p != q) alias[std::max(p, q)] = std::min(p, q);
				}
	}

	// The faces' corners as the triangulation's vertices (`corners`).
	void insert_corners(const std::vector<int>& on, const std::vector<Face>& faces)
	{
		std::map<int, CDT::Vertex_handle> at;
		for (int f : on) {
			Corners c;
			for (int k = 0; k < 3; ++k) {
				const int v = root(faces[f].t[k]);
				auto [it, fresh] = at.emplace(v, CDT::Vertex_handle());
				if (fresh) {
					it->second = cdt.insert(P2(u.dot(V[v]), w.dot(V[v])));
					if (it->second->info().v < 0) it->second->info().v = v;
					else if (it->second->info().v != v) alias[v] = it->second->info().v;   // same double point
				}
				c[k] = it->second;
			}
			corners.push_back(c);
		}
	}

	// Every edge of the faces on the plane a constraint; crossings become vertices (exact).
	void constrain_edges()
	{
		for (const Corners& c : corners)
			for (int k = 0; k < 3; ++k)
				if (c[k] != c[(k + 1) % 3]) cdt.insert_constraint(c[k], c[(k + 1) % 3]);
	}

	// Each side's faces on the plane turned up and those turned down, each class one region: only the
	// regions' boundaries are constraints, and the classes covering a triangle are counted by crossing
	// them from outside. The two sides' own triangulations of one cap (fans from different corners)
	// would cross each other at up to quadratically many points, each an exact construction. False
	// where a class is no such region (an edge used twice in one direction, counts that disagree):
	// covered_once then decides face by face. A face whose corners lie on one line covers nothing and
	// is left out: the edges around it then bound the region along both its sides, and crossing it
	// counts its class twice, that is not at all.
	bool by_boundaries(const std::vector<int>& on, const std::vector<Face>& faces, std::vector<Face>& kept)
	{
		std::vector<int> cls(on.size(), -1);   // 2 * side + (turned clockwise); -1: on one line
		std::map<std::pair<CDT::Vertex_handle, CDT::Vertex_handle>, int> uses[4];   // directed edge -> uses
		for (size_t i = 0; i < on.size(); ++i) {
			const Corners& c = corners[i];
			const int      o = CGAL::orientation(c[0]->point(), c[1]->point(), c[2]->point());
			if (o == CGAL::COLLINEAR) continue;
			cls[i] = 2 * faces[on[i]].from + (o == CGAL::CLOCKWISE);
			for (int k = 0; k < 3; ++k)
				if (c[k] != c[(k + 1) % 3] && ++uses[cls[i]][{c[k], c[(k + 1) % 3]}] > 1) return false;
		}
		// Each boundary edge once, as first used: keyed by the solid's vertex ids, not the handles'
		// addresses, whose order depends on the allocator (and so on the thread).
		std::vector<std::pair<CDT::Vertex_handle, CDT::Vertex_handle>> edges;
		std::map<std::pair<int, int>, int>                             classes;
		for (size_t i = 0; i < on.size(); ++i)
			for (int k = 0; k < 3 && cls[i] >= 0; ++k) {
				const CDT::Vertex_handle a = corners[i][k], b = corners[i][(k + 1) % 3];
				if (a == b || uses[cls[i]].count({b, a})) continue;   // inside the class's region
				const auto key = std::minmax(a->info().v, b->info().v);
				if (!classes.count(key)) edges.push_back({a, b});
				classes[key] ^= 1 << cls[i];
			}
		std::map<std::size_t, int> bounds;   // constraint -> the classes it bounds
		for (const auto& [a, b] : edges) {
			const int m = classes[std::minmax(a->info().v, b->info().v)];
			if (m) bounds[cdt.insert_constraint(a, b).index()] = m;
		}
		std::map<CDT::Face_handle, int> in;   // triangle -> the classes covering it
		if (!count_sides(bounds, in)) return false;
		for (const CDT::Face_handle fh : cdt.finite_face_handles()) {
			const int m = in[fh];
			if (m == 0 || (m & (m - 1))) continue;   // none, or more than one
			const int c = m == 1 ? 0 : m == 2 ? 1 : m == 4 ? 2 : 3;
			keep(fh, c / 2, c % 2 == 1, kept);
		}
		return true;
	}

	// The classes covering each triangle (by_boundaries), from outside (none) across the boundaries;
	// false where two ways to a triangle disagree.
	bool count_sides(const std::map<std::size_t, int>& bounds, std::map<CDT::Face_handle, int>& in) const
	{
		const auto crossed = [&](CDT::Face_handle f, int k) {
			int m = 0;
			if (!f->is_constrained(k)) return m;
			const CDT::Vertex_handle a = f->vertex(cdt.cw(k)), b = f->vertex(cdt.ccw(k));
			for (auto c = cdt.contexts_begin(a, b); c != cdt.contexts_end(a, b); ++c) {
				const auto it = bounds.find(c->id().index());
				if (it != bounds.end()) m ^= it->second;
			}
			return m;
		};
		std::vector<CDT::Face_handle> todo{cdt.infinite_face()};
		in[cdt.infinite_face()] = 0;
		while (!todo.empty()) {
			const CDT::Face_handle f = todo.back();
			todo.pop_back();
			for (int k = 0; k < 3; ++k) {
				const CDT::Face_handle g = f->neighbor(k);
				const int              m = in[f] ^ crossed(f, k);
				const auto [it, fresh]   = in.emplace(g, m);
				if (fresh) todo.push_back(g);
				else if (it->second != m) return false;
			}
		}
		return true;
	}

	// The triangles exactly one face covers, oriented as that face. Each face's triangles are found
	// from its first corner outwards, across edges, while their centre stays inside it.
	std::vector<Face> covered_once(const std::vector<int>& on, const std::vector<Face>& faces)
	{
		std::map<CDT::Face_handle, std::pair<int, int>> cover;   // triangle -> (faces over it, the last)
		for (size_t i = 0; i < on.size(); ++i) {
			const Corners& c = corners[i];
			if (CGAL::orientation(c[0]->point(), c[1]->point(), c[2]->point()) == CGAL::COLLINEAR) continue;
			std::vector<CDT::Face_handle> todo;
			std::set<CDT::Face_handle>    seen;
			auto                          fc = cdt.incident_faces(c[0]), end = fc;
			do
				if (!cdt.is_infinite(fc) && inside(c, fc)) todo.push_back(fc), seen.insert(fc);
			while (++fc != end);
			while (!todo.empty()) {
				const CDT::Face_handle fh = todo.back();
				todo.pop_back();
				auto& [n, last] = cover[fh];
				++n, last = (int) i;
				for (int k = 0; k < 3; ++k) {
					const CDT::Face_handle g = fh->neighbor(k);
					if (!cdt.is_infinite(g) && !seen.count(g) && inside(c, g)) todo.push_back(g), seen.insert(g);
				}
			}
		}
		std::vector<Face> kept;
		for (const CDT::Face_handle fh : cdt.finite_face_handles()) {   // the triangulation's order, not the map's
			const auto it = cover.find(fh);
			if (it == cover.end() || it->second.first != 1) continue;
			const int      i = it->second.second;
			const Corners& c = corners[i];
			keep(fh, faces[on[i]].from, CGAL::orientation(c[0]->point(), c[1]->point(), c[2]->point()) == CGAL::CLOCKWISE, kept);
		}
		return kept;
	}

	// Triangle fh as a face of side `from`, turned as that side's face is (`turned`: clockwise in the
	// plane's frame); slivers are left out.
	void keep(CDT::Face_handle fh, int from, bool turned, std::vector<Face>& kept)
	{
		Face f;
		f.from = from;
		for (int k = 0; k < 3; ++k) f.t[turned ? 2 - k : k] = vertex(fh->vertex(k));
		if (!needle(f.t)) kept.push_back(f);
	}

	// Triangle fh's centre lies inside face c (the triangulation's triangles are wholly in or out).
	static bool inside(const Corners& c, CDT::Face_handle fh)
	{
		const P2 m = CGAL::centroid(fh->vertex(0)->point(), fh->vertex(1)->point(), fh->vertex(2)->point());
		const CGAL::Orientation o = CGAL::orientation(c[0]->point(), c[1]->point(), c[2]->point());
		return CGAL::orientation(c[0]->point(), c[1]->point(), m) == o && CGAL::orientation(c[1]->point(), c[2]->point(), m) == o &&
		       CGAL::orientation(c[2]->point(), c[0]->point(), m) == o;
	}

	// A sliver of the seam no wider than eps once rounded (its corners on one line, or snapped
	// together): dropped, its long edge's neighbour gets its middle corner (close_rims).
	bool needle(const Tri& t) const
	{
		if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return true;
		double longest = 0;
		for (int k = 0; k < 3; ++k) longest = std::max(longest, (V[t[(k + 1) % 3]] - V[t[k]]).norm());
		return (V[t[1]] - V[t[0]]).cross(V[t[2]] - V[t[0]]).norm() <= eps * longest;
	}

	int root(int v) const { return renamed(v, alias); }

	// The solid's vertex, or a crossing: the solid's vertex within eps of it, else a new vertex lifted
	// onto the plane (made once).
	int vertex(CDT::Vertex_handle vh)
	{
		if (vh->info().v < 0) {
			const Eigen::Vector2d p(CGAL::to_double(vh->point().x()), CGAL::to_double(vh->point().y()));
			const auto lo = std::lower_bound(flat.begin(), flat.end(), p.x() - eps, [](const auto& q, double x) { return q.first.x() < x; });
			for (auto it = lo; it != flat.end() && it->first.x() <= p.x() + eps && vh->info().v < 0; ++it)
				if ((it->first - p).norm() <= eps) vh->info().v = root(it->second);
			if (vh->info().v < 0) {
				V.push_back(pl.n * pl.d + p.x() * u + p.y() * w);
				vh->info().v = (int) V.size() - 1;
			}
		}
		return vh->info().v;
	}
};

// Slivers a rounding error wide that the seams leave (the exact triangulation keeps them; they
// collapse to zero area once rounded): CGAL's repair (exact predicates) collapses or flips them away.
TriMesh without_needles(const TriMesh& m)
{
	using IK = CGAL::Exact_predicates_inexact_constructions_kernel;
	using SM = CGAL::Surface_mesh<IK::Point_3>;
	// Most seams leave none: then the repair has nothing to do (its test, exact collinearity, first).
	const auto point = [&](int v) { return IK::Point_3(m.V[v].x(), m.V[v].y(), m.V[v].z()); };
	if (std::none_of(m.F.begin(), m.F.end(), [&](const Tri& t) { return CGAL::collinear(point(t[0]), point(t[1]), point(t[2])); }))
		return m;
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
	for (const Plane& pl : planes) PlaneSeam(V, pl, eps, alias).cut(faces);
	TriMesh all;
	all.V = std::move(V);
	for (const Face& f : faces) {
		if (f.dropped) continue;
		Tri t = f.t;
		for (int& v : t) v = renamed(v, alias);
		if (t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) all.F.push_back(t);
	}
	close_rims(all, eps);
	return without_needles(compacted(all));
}

} // namespace acd
