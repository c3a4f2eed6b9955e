#include "acd/prepare/fill_holes.h"
#include "acd/mesh/orient.h"
#include "acd/prepare/plane_fill.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <iterator>
#include <map>
#include <numeric>
#include <tuple>
#include <utility>
#include <vector>

namespace acd {

namespace {

using K     = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using SMesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

// Fairing solves for the patch with the rings around its rim held: three rings hold what it needs.
constexpr int kRings = 3;
// Rims up to this long may fall back to the triangulation search whose cost grows with the cube of
// their length (27 million steps here) when no patch is found among the Delaunay faces.
constexpr size_t kCubicRim = 300;
// Points within this share of the surface's box diagonal of a plane lie on it (plane_fill.h).
constexpr double kOnPlane = 1e-6;

struct Edge
{
	int a, b;   // a < b
	int from;   // the face's direction: a -> b (0) or b -> a (1)
	bool operator<(const Edge& o) const { return std::tie(a, b, from) < std::tie(o.a, o.b, o.from); }
};

// The surface's border edges, each as its face runs it (from, to); false for an edge of more than two
// faces or of two faces running it the same way (the patches could not be oriented).
bool border_edges(const TriMesh& m, std::vector<std::pair<int, int>>& border)
{
	std::vector<Edge> e;
	e.reserve(3 * m.F.size());
	for (int f = 0; f < (int) m.F.size(); ++f)
		for (int k = 0; k < 3; ++k) {
			const int u = m.F[f][k], v = m.F[f][(k + 1) % 3];
			e.push_back({std::min(u, v), std::max(u, v), u > v});
		}
	std::sort(e.begin(), e.end());
	for (size_t i = 0, j = 0; i < e.size(); i = j) {
		for (j = i; j < e.size() && e[j].a == e[i].a && e[j].b == e[i].b;) ++j;
		if (j - i > 2 || (j - i == 2 && e[i].from == e[i + 1].from)) return false;
		if (j - i == 1) border.emplace_back(e[i].from ? e[i].b : e[i].a, e[i].from ? e[i].a : e[i].b);
	}
	return true;
}

// Border halfedges of a hole as (least, greatest) vertex, sorted.
using Rim = std::vector<std::pair<int, int>>;

// The border's pieces connected through shared vertices (a hole, or holes that touch at a corner): each
// as its vertices and its rim, in the order of their least vertex.
struct Hole
{
	std::vector<int> vertices;
	Rim              rim;
	bool operator<(const Hole& o) const { return vertices < o.vertices; }
};

std::vector<Hole> border_pieces(const std::vector<std::pair<int, int>>& border, size_t nv)
{
	std::vector<int> root(nv);
	std::iota(root.begin(), root.end(), 0);
	const auto find = [&](int v) {
		while (root[v] != v) v = root[v] = root[root[v]];
		return v;
	};
	for (const auto& [u, v] : border) root[find(u)] = find(v);
	std::map<int, Hole> by_root;
	std::vector<char>   seen(nv, 0);
	for (const auto& [u, v] : border) {
		Hole& h = by_root[find(u)];
		h.rim.push_back(std::minmax(u, v));
		for (int w : {u, v})
			if (!seen[w]) seen[w] = 1, h.vertices.push_back(w);
	}
	std::vector<Hole> holes;
	for (auto& [r, h] : by_root) {
		std::sort(h.vertices.begin(), h.vertices.end());
		std::sort(h.rim.begin(), h.rim.end());
		holes.push_back(std::move(h));
	}
	std::sort(holes.begin(), holes.end());   // repeatable: by least vertex
	return holes;
}

// Faces of each vertex (compressed rows).
struct VertexFaces
{
	std::vector<int> start, face;
	VertexFaces(const TriMesh& m) : start(m.V.size() + 1, 0)
	{
		for (const Tri& t : m.F)
			for (int v : t) ++start[v + 1];
		std::partial_sum(start.begin(), start.end(), start.begin());
		face.resize(start.back());
		std::vector<int> at(start.begin(), start.end() - 1);
		for (int f = 0; f < (int) m.F.size(); ++f)
			for (int v : m.F[f]) face[at[v]++] = f;
	}
};

// The faces within kRings rings of a hole's vertices, ascending. `vin` (a flag per vertex, all clear)
// is scratch shared by the holes, so that each costs what its rings hold, not the surface's size.
std::vector<int> rings_about(const TriMesh& m, const VertexFaces& vf, const std::vector<int>& hole, std::vector<char>& vin)
{
	std::vector<int>    verts = hole, faces, seen = hole;
	std::map<int, char> fin;
	for (int v : hole) vin[v] = 1;
	for (int r = 0; r < kRings; ++r) {
		std::vector<int> next;
		for (int v : verts)
			for (int i = vf.start[v]; i < vf.start[v + 1]; ++i)
				if (!fin[vf.face[i]]++) {
					faces.push_back(vf.face[i]);
					for (int w : m.F[vf.face[i]])
						if (!vin[w]) vin[w] = 1, next.push_back(w), seen.push_back(w);
				}
		verts = std::move(next);
	}
	for (int v : seen) vin[v] = 0;
	std::sort(faces.begin(), faces.end());
	return faces;
}

// One hole's neighbourhood as a halfedge mesh; `global[i]` is the surface's index of its vertex i.
bool local_mesh(const TriMesh& m, const std::vector<int>& faces, SMesh& out, std::vector<int>& global)
{
	std::map<int, std::size_t>               local;
	std::vector<Point>                       pts;
	std::vector<std::array<std::size_t, 3>> soup;
	for (int f : faces) {
		std::array<std::size_t, 3> t;
		for (int k = 0; k < 3; ++k) {
			const int  v  = m.F[f][k];
			const auto it = local.emplace(v, pts.size());
			if (it.second) {
				pts.emplace_back(m.V[v].x(), m.V[v].y(), m.V[v].z());
				global.push_back(v);
			}
			t[k] = it.first->second;
		}
		soup.push_back(t);
	}
	// A vertex where two holes touch joins two fans of faces: it becomes one vertex per fan, each copy
	// standing for the same vertex of the surface.
	if (!PMP::is_polygon_soup_a_polygon_mesh(soup)) {
		const size_t before = pts.size();
		PMP::orient_polygon_soup(pts, soup);
		if (!PMP::is_polygon_soup_a_polygon_mesh(soup)) return false;
		std::map<std::tuple<double, double, double>, int> at;
		for (size_t i = 0; i < before; ++i) at.emplace(std::make_tuple(pts[i].x(), pts[i].y(), pts[i].z()), global[i]);
		for (size_t i = before; i < pts.size(); ++i) global.push_back(at.at(std::make_tuple(pts[i].x(), pts[i].y(), pts[i].z())));
	}
	PMP::polygon_soup_to_polygon_mesh(pts, soup, out);
	return true;
}

// Border halfedges of the local mesh, one per cycle, whose edges are all the hole's `rim`: not the border
// of the neighbourhood, though its vertices be the hole's, nor another hole within it.
std::vector<SMesh::Halfedge_index> cycles_of(const SMesh& m, const std::vector<int>& global, const Rim& rim)
{
	std::vector<SMesh::Halfedge_index> cycles;
	std::vector<char>                  seen(m.number_of_halfedges(), 0);
	for (SMesh::Halfedge_index h : m.halfedges()) {
		if (!m.is_border(h) || seen[h.idx()]) continue;
		bool hole = true;
		for (SMesh::Halfedge_index g = h; !seen[g.idx()]; g = m.next(g)) {
			seen[g.idx()] = 1;
			const std::pair<int, int> e = std::minmax(global[m.source(g).idx()], global[m.target(g).idx()]);
			hole           = hole && std::binary_search(rim.begin(), rim.end(), e);
		}
		if (hole) cycles.push_back(h);
	}
	return cycles;
}

struct Patch
{
	std::vector<Vec3> V;   // new vertices
	std::vector<Tri>  F;   // faces: >= 0 a vertex of the surface, < 0 new vertex -1 - i
	int               faired = 0;
};

// Whether the patch leaves an edge between two of the surface's vertices with other than two faces: a
// face repeated or an edge of three faces. So it does where holes touch at a corner (the corner is one
// vertex per fan for the fill, which cannot see that an edge from one copy repeats one from the other),
// and about a face whose every edge is on the border.
bool breaks_edges(const TriMesh& m, const std::vector<int>& faces, const std::vector<Tri>& patch)
{
	std::vector<std::pair<int, int>> edges, joined;
	for (int f : faces)
		for (int k = 0; k < 3; ++k) edges.push_back(std::minmax(m.F[f][k], m.F[f][(k + 1) % 3]));
	for (const Tri& t : patch)
		for (int k = 0; k < 3; ++k)
			if (t[k] >= 0 && t[(k + 1) % 3] >= 0) {
				edges.push_back(std::minmax(t[k], t[(k + 1) % 3]));
				joined.push_back(edges.back());
			}
	std::sort(edges.begin(), edges.end());
	for (const std::pair<int, int>& e : joined) {
		const auto [lo, hi] = std::equal_range(edges.begin(), edges.end(), e);
		if (hi - lo != 2) return true;
	}
	return false;
}

// The hole's border edges as their faces run them, with those faces.
std::vector<RimEdge> rim_edges(const TriMesh& m, const VertexFaces& vf, const Rim& rim)
{
	std::vector<RimEdge> out;
	for (const auto& [a, b] : rim)
		for (int i = vf.start[a]; i < vf.start[a + 1]; ++i) {
			const Tri& t = m.F[vf.face[i]];
			for (int k = 0; k < 3; ++k) {
				const int u = t[k], v = t[(k + 1) % 3];
				if ((u == a && v == b) || (u == b && v == a)) out.push_back({u, v, vf.face[i]});
			}
		}
	return out;
}

// Whether the patch crosses itself or the faces about the hole.
bool crosses(const TriMesh& m, const std::vector<int>& faces, const Patch& p)
{
	std::map<int, size_t>              local;
	std::vector<Point>                 pts;
	std::vector<std::array<size_t, 3>> soup;
	const auto at = [&](int v) {
		const auto it = local.emplace(v, pts.size());
		if (it.second) {
			const Vec3& q = v >= 0 ? m.V[v] : p.V[-1 - v];
			pts.emplace_back(q.x(), q.y(), q.z());
		}
		return it.first->second;
	};
	for (int f : faces) soup.push_back({at(m.F[f][0]), at(m.F[f][1]), at(m.F[f][2])});
	for (const Tri& t : p.F) soup.push_back({at(t[0]), at(t[1]), at(t[2])});
	return PMP::does_triangle_soup_self_intersect(pts, soup);
}

// The hole closed on the planes its rim runs on (plane_fill.h), if it is such a hole and the patch
// neither crosses the faces about it nor repeats an edge of the surface.
std::optional<Patch> plane_one(const TriMesh& m, const std::vector<int>& faces, const std::vector<RimEdge>& rim, double eps)
{
	std::optional<PlanePatch> pp = plane_patch(m, rim, eps, faces);
	if (!pp) return std::nullopt;
	Patch p;
	p.V = std::move(pp->corners);
	p.F = std::move(pp->faces);
	if (breaks_edges(m, faces, p.F) || crosses(m, faces, p)) return std::nullopt;
	return p;
}

// The hole filled in its neighbourhood, faired or flat; empty when the triangulation finds no patch, or
// (faired) when the patch crosses the neighbourhood.
std::optional<Patch> fill_one(const TriMesh& m, const std::vector<int>& faces, const Rim& rim, bool fair)
{
	SMesh            sm;
	std::vector<int> global;
	if (!local_mesh(m, faces, sm, global)) return std::nullopt;
	const size_t     old_v = global.size();
	std::vector<SMesh::Face_index> patch;
	Patch            p;
	for (SMesh::Halfedge_index h : cycles_of(sm, global, rim)) {
		const size_t before = patch.size();
		// The 3D Delaunay search first; the cubic search over all triangulations only for a short rim.
		const auto np = CGAL::parameters::face_output_iterator(std::back_inserter(patch))
		                    .do_not_use_cubic_algorithm(rim.size() > kCubicRim);
		if (fair) p.faired += std::get<0>(PMP::triangulate_refine_and_fair_hole(sm, h, np));
		else PMP::triangulate_and_refine_hole(sm, h, np);
		if (patch.size() == before) return std::nullopt;
	}
	if (patch.empty()) return std::nullopt;
	if (fair) {
		std::vector<char> is_patch(sm.number_of_faces() + sm.number_of_removed_faces(), 0);
		for (SMesh::Face_index f : patch) is_patch[f.idx()] = 1;
		std::vector<std::pair<SMesh::Face_index, SMesh::Face_index>> crossing;
		PMP::self_intersections(sm, std::back_inserter(crossing));
		for (const auto& [f, g] : crossing)
			if (is_patch[f.idx()] || is_patch[g.idx()]) return std::nullopt;
	}
	std::vector<int> id(sm.number_of_vertices() + sm.number_of_removed_vertices(), 0);
	for (SMesh::Vertex_index v : sm.vertices())
		if (v.idx() < old_v) id[v.idx()] = global[v.idx()];
		else {
			id[v.idx()]    = -1 - (int) p.V.size();
			const Point& q = sm.point(v);
			p.V.emplace_back(q.x(), q.y(), q.z());
		}
	for (SMesh::Face_index f : patch) {
		const SMesh::Halfedge_index h = sm.halfedge(f);
		p.F.push_back({id[sm.source(h).idx()], id[sm.target(h).idx()], id[sm.target(sm.next(h)).idx()]});
	}
	if (breaks_edges(m, faces, p.F)) return std::nullopt;
	return p;
}

} // namespace

std::optional<FilledHoles> fill_holes(const TriMesh& surface, int max_holes, int max_rim)
{
	TriMesh m;
	m.V = surface.V;
	for (const Tri& t : surface.F) {
		for (int v : t)
			if (v < 0 || v >= (int) m.V.size() || !m.V[v].allFinite()) return std::nullopt;
		if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) m.F.push_back(t);
	}
	orient_patches(m);
	std::vector<std::pair<int, int>> border;
	if (m.F.empty() || !border_edges(m, border) || border.empty()) return std::nullopt;
	const std::vector<Hole> holes = border_pieces(border, m.V.size());
	if ((int) holes.size() > max_holes) return std::nullopt;
	for (const Hole& h : holes)
		if ((int) h.rim.size() > max_rim) return std::nullopt;
	const VertexFaces vf(m);
	std::vector<char> vin(m.V.size(), 0);
	Vec3 lo = m.V[m.F[0][0]], hi = lo;
	for (const Tri& t : m.F)
		for (int v : t) lo = lo.cwiseMin(m.V[v]), hi = hi.cwiseMax(m.V[v]);
	const double eps = kOnPlane * (hi - lo).norm();
	FilledHoles       r;
	r.mesh        = m;
	r.first_patch = m.F.size();
	for (const Hole& hole : holes) {
		const std::vector<int> faces = rings_about(m, vf, hole.vertices, vin);
		std::optional<Patch>   p     = plane_one(m, faces, rim_edges(m, vf, hole.rim), eps);
		r.planar += p.has_value();
		if (!p) p = fill_one(m, faces, hole.rim, true);
		if (!p) p = fill_one(m, faces, hole.rim, false);
		if (!p) return std::nullopt;
		const int base = (int) r.mesh.V.size();
		r.mesh.V.insert(r.mesh.V.end(), p->V.begin(), p->V.end());
		for (Tri t : p->F) {
			for (int& v : t)
				if (v < 0) v = base - 1 - v;
			r.mesh.F.push_back(t);
		}
		++r.holes;
		r.faired += p->faired > 0;
	}
	return r;
}

} // namespace acd
