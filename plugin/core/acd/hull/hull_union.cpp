#include "acd/hull/hull_union.h"
#include "acd/hull/hull.h"
#include "acd/mesh/measures.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

namespace acd {

namespace {

template <class SM> SM to_surface_mesh(const TriMesh& m)
{
	using P = typename SM::Point;
	std::vector<P>                     pts;
	std::vector<std::array<size_t, 3>> faces;
	for (const Vec3& v : m.V) pts.emplace_back(v.x(), v.y(), v.z());
	for (const Tri& t : m.F) faces.push_back({(size_t) t[0], (size_t) t[1], (size_t) t[2]});
	SM out;
	CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(pts, faces, out);
	return out;
}

// Facet planes of a hull (ConvexHull merges coplanar triangles and ignores slivers, whose normals
// in a raw triangulation are rounding noise and would cut the hull).
std::vector<Plane> planes_of(const TriMesh& h)
{
	try {
		return ConvexHull(h.V).facet_plane;
	}
	catch (const Error&) {   // a flat hull holds no volume
		return {};
	}
}

} // namespace

TriMesh merge_hulls(const std::vector<TriMesh>& hulls, bool boolean)
{
	TriMesh out;
	if (!boolean) {
		for (const TriMesh& h : hulls) append(out, h);
		return out;
	}
	using EK = CGAL::Exact_predicates_exact_constructions_kernel;
	using SM = CGAL::Surface_mesh<EK::Point_3>;
	namespace PMP = CGAL::Polygon_mesh_processing;
	SM acc;
	bool first = true;
	for (const TriMesh& h : hulls) {
		if (h.F.empty()) continue;
		SM next = to_surface_mesh<SM>(h);
		if (first) {
			acc   = std::move(next);
			first = false;
			continue;
		}
		SM result;
		if (!PMP::corefine_and_compute_union(acc, next, result))
			throw Error(Error::Internal, "The boolean union of the hulls failed (CGAL corefinement).");
		acc = std::move(result);
	}
	std::map<SM::Vertex_index, int> id;
	for (auto v : acc.vertices()) {
		const auto& p = acc.point(v);
		id[v]         = (int) out.V.size();
		out.V.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
	}
	for (auto f : acc.faces()) {
		Tri t;
		int k = 0;
		for (auto v : CGAL::vertices_around_face(acc.halfedge(f), acc)) {
			if (k < 3) t[k] = id[v];
			++k;
		}
		if (k == 3) out.F.push_back(t);
	}
	return out;
}

double volume_iou(const TriMesh& mesh, const std::vector<TriMesh>& hulls, int samples, unsigned seed,
                  double* stderr_out)
{
	using K  = CGAL::Exact_predicates_inexact_constructions_kernel;
	using SM = CGAL::Surface_mesh<K::Point_3>;
	const SM                       sm = to_surface_mesh<SM>(mesh);
	CGAL::Side_of_triangle_mesh<SM, K> side(sm);
	std::vector<std::vector<Plane>> planes;
	Eigen::AlignedBox3d box;
	for (const Vec3& v : mesh.V) box.extend(v);
	for (const TriMesh& h : hulls) {
		planes.push_back(planes_of(h));
		for (const Vec3& v : h.V) box.extend(v);
	}
	std::mt19937                           rng(seed);
	std::uniform_real_distribution<double> u(0, 1);
	long                                   both = 0, either = 0;
	for (int i = 0; i < samples; ++i) {
		const Vec3 p  = box.min() + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(box.max() - box.min());
		const bool in = side(K::Point_3(p.x(), p.y(), p.z())) != CGAL::ON_UNBOUNDED_SIDE;
		bool       inh = false;
		for (const auto& pl : planes) {
			bool all = !pl.empty();
			for (const Plane& f : pl)
				if (f.eval(p) > 0) {
					all = false;
					break;
				}
			if (all) {
				inh = true;
				break;
			}
		}
		both += in && inh;
		either += in || inh;
	}
	const double iou = either ? double(both) / double(either) : 0;
	if (stderr_out) *stderr_out = either ? std::sqrt(iou * (1 - iou) / double(either)) : 0;
	return iou;
}

} // namespace acd
