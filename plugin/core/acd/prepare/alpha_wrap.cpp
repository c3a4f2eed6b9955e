#include "acd/prepare/alpha_wrap.h"
#include "acd/mesh/measures.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/alpha_wrap_3.h>

#include <cmath>

namespace acd {

TriMesh alpha_wrap(const TriMesh& in, double alpha, double offset)
{
	using K     = CGAL::Exact_predicates_inexact_constructions_kernel;
	using Point = K::Point_3;
	if (!(alpha > 0) || !(offset > 0) || !std::isfinite(alpha) || !std::isfinite(offset))
		throw Error(Error::InvalidOption, "The alpha wrap's alpha and offset must be positive lengths.");

	std::vector<Point> pts;
	std::vector<int>   id(in.V.size(), -1);
	std::vector<Vec3>  finite;
	for (size_t i = 0; i < in.V.size(); ++i)
		if (in.V[i].allFinite()) {
			id[i] = (int) pts.size();
			pts.emplace_back(in.V[i].x(), in.V[i].y(), in.V[i].z());
			finite.push_back(in.V[i]);
		}
	if (pts.empty()) throw Error(Error::InvalidInput, "The mesh has no vertex with finite coordinates to wrap.");
	std::vector<std::array<std::size_t, 3>> faces;
	for (const Tri& t : in.F) {
		bool ok = true;
		for (int v : t) ok = ok && v >= 0 && v < (int) in.V.size() && id[v] >= 0;
		if (ok) faces.push_back({(std::size_t) id[t[0]], (std::size_t) id[t[1]], (std::size_t) id[t[2]]});
	}
	// The wrap's size grows like (size / alpha)^2: refuse what would not finish in reasonable memory.
	const double size = extent(finite);
	if (!(size > 0)) throw Error(Error::InvalidInput, "All vertices coincide: there is nothing to wrap.");
	if (size / alpha > 2000)
		throw Error(Error::InvalidOption, "The alpha wrap's alpha is below 1/2000 of the mesh's size; "
		                                  "the wrap would be too large. Use a larger alpha.");

	CGAL::Surface_mesh<Point> wrap;
	if (faces.empty()) CGAL::alpha_wrap_3(pts, alpha, offset, wrap);
	else CGAL::alpha_wrap_3(pts, faces, alpha, offset, wrap);

	TriMesh out;
	std::vector<int> vid(wrap.number_of_vertices() + wrap.number_of_removed_vertices(), -1);
	for (auto v : wrap.vertices()) {
		vid[v.idx()] = (int) out.V.size();
		const Point& p = wrap.point(v);
		out.V.emplace_back(p.x(), p.y(), p.z());
	}
	for (auto f : wrap.faces()) {
		Tri t;
		int k = 0;
		for (auto v : CGAL::vertices_around_face(wrap.halfedge(f), wrap)) {
			if (k == 3) throw Error(Error::Internal, "The alpha wrap returned a face that is not a triangle.");
			t[k++] = vid[v.idx()];
		}
		out.F.push_back(t);
	}
	return out;
}

} // namespace acd
