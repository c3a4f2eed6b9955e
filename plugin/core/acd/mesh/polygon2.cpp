#include "acd/mesh/polygon2.h"
#include "acd/mesh/measures.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <exception>

namespace acd {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

} // namespace

double signed_area(const Loop2& l)
{
	double a = 0;
	for (size_t i = 0, j = l.size() - 1; i < l.size(); j = i++) a += cross(l[j], l[i]);
	return a / 2;
}

double area(const Polygon2& p)
{
	double a = signed_area(p.outer);
	for (const Loop2& h : p.holes) a += signed_area(h);   // holes are clockwise: negative
	return a;
}

bool inside(const Loop2& poly, const Vec2& p)
{
	bool in = false;
	for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
		const Vec2 &a = poly[i], &b = poly[j];
		if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
			in = !in;
	}
	return in;
}

bool triangulate(const Polygon2& p, std::vector<Vec2>& V, std::vector<Tri>& F)
{
	using Vb  = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
	using Fbi = CGAL::Triangulation_face_base_with_info_2<int, K>;
	using Fb  = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
	using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb, Fb>,
	                                                       CGAL::No_constraint_intersection_tag>;
	V.clear();
	F.clear();
	CDT cdt;
	try {
		for (int l = 0; l <= (int) p.holes.size(); ++l) {
			const Loop2&                    L = l == 0 ? p.outer : p.holes[l - 1];
			std::vector<CDT::Vertex_handle> vh;
			for (const Vec2& q : L) {
				vh.push_back(cdt.insert(K::Point_2(q.x(), q.y())));
				vh.back()->info() = (int) V.size();
				V.push_back(q);
			}
			for (size_t i = 0; i < vh.size(); ++i) cdt.insert_constraint(vh[i], vh[(i + 1) % vh.size()]);
		}
	}
	catch (const std::exception&) {
		return false;   // crossing constraints
	}
	if (cdt.number_of_vertices() != V.size()) return false;   // two points merged
	// Inside = odd nesting level, flooding from the infinite face across constraints.
	for (auto f : cdt.all_face_handles()) f->info() = -1;
	std::vector<std::pair<CDT::Face_handle, int>> seeds{{cdt.infinite_face(), 0}};
	for (size_t i = 0; i < seeds.size(); ++i) {
		auto [seed, level] = seeds[i];
		if (seed->info() != -1) continue;
		seed->info() = level;
		std::vector<CDT::Face_handle> stack{seed};
		while (!stack.empty()) {
			auto f = stack.back();
			stack.pop_back();
			for (int e = 0; e < 3; ++e) {
				auto g = f->neighbor(e);
				if (g->info() != -1) continue;
				if (cdt.is_constrained(CDT::Edge(f, e))) seeds.emplace_back(g, level + 1);
				else {
					g->info() = level;
					stack.push_back(g);
				}
			}
		}
	}
	for (auto f : cdt.finite_face_handles())
		if (f->info() % 2 == 1) F.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
	return !F.empty();
}

} // namespace acd
