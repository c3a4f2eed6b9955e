// Neutral scores for a set of convex hulls against the solid they approximate, computed the same
// way whatever method made the hulls (the benchmark runs it on every method's output):
//   acd_metrics input.obj hulls.obj [samples]
// Prints one JSON object:
//   hull_error: largest distance from the surface of the union of the hulls to the input surface
//               (area-uniform samples on each hull, dropping those inside or on another hull, such
//               as the shared faces of two parts cut by one plane), as a
//               fraction of the input's bounding-box diagonal; hull_error_mean likewise.
//   hull_error_outside, hull_error_inside: the same samples split by the side of the input they lie
//               on (closed input only, else null): how far the hulls reach out of the solid (false
//               contacts) and how deep the union's boundary lies inside it (gaps between hulls).
//   iou:        volume IoU of the union of hulls and the input solid, by uniform Monte Carlo samples
//               in the common bounding box; iou_stderr its standard error. null if the input is not closed.
#include "acd/hull/hull.h"
#include "obj_io.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits_3.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <random>

using K     = CGAL::Exact_predicates_inexact_constructions_kernel;
using SMesh = CGAL::Surface_mesh<K::Point_3>;
using Prim  = CGAL::AABB_face_graph_triangle_primitive<SMesh>;
using Tree  = CGAL::AABB_tree<CGAL::AABB_traits_3<K, Prim>>;

namespace {
struct Hull
{
	acd::ConvexHull  h;
	Eigen::AlignedBox3d box;
	bool covers(const acd::Vec3& p, double tol) const   // inside or on the boundary, within tol
	{
		if ((p.array() < box.min().array() - tol).any() || (p.array() > box.max().array() + tol).any()) return false;
		for (const acd::Plane& pl : h.facet_plane)
			if (pl.eval(p) > tol) return false;
		return true;
	}
	bool contains(const acd::Vec3& p) const
	{
		if (!box.contains(p)) return false;
		for (const acd::Plane& pl : h.facet_plane)
			if (pl.eval(p) > 0) return false;
		return true;
	}
};
}

int main(int argc, char** argv)
{
	if (argc < 3) {
		std::fprintf(stderr, "usage: %s input.obj hulls.obj [samples]\n", argv[0]);
		return 2;
	}
	const long samples = argc > 3 ? std::atol(argv[3]) : 200000;
	try {
		const acd::TriMesh in = acd::bench::read_obj(argv[1]);
		SMesh              sm;
		std::vector<SMesh::Vertex_index> vs;
		for (const acd::Vec3& p : in.V) vs.push_back(sm.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
		bool soup_ok = true;
		for (const acd::Tri& t : in.F)
			if (sm.add_face(vs[t[0]], vs[t[1]], vs[t[2]]) == SMesh::null_face()) soup_ok = false;
		const bool closed = soup_ok && CGAL::is_closed(sm);
		Tree       tree(faces(sm).first, faces(sm).second, sm);
		tree.accelerate_distance_queries();
		Eigen::AlignedBox3d ibox;
		for (const acd::Vec3& p : in.V) ibox.extend(p);
		const double diag = ibox.diagonal().norm();

		std::vector<Hull> hulls;
		int               degenerate = 0;
		for (const acd::TriMesh& o : acd::bench::read_obj_objects(argv[2])) {
			try {
				Hull h{acd::ConvexHull(o.V), {}};
				for (const acd::Vec3& p : h.h.points) h.box.extend(p);
				hulls.push_back(std::move(h));
			}
			catch (const acd::Error&) {
				++degenerate;   // flat or empty: no volume, no surface worth scoring
			}
		}
		if (hulls.empty()) throw std::runtime_error("no hull with volume");

		std::mt19937_64                        rng(12345);
		std::uniform_real_distribution<double> U(0, 1);
		// Hull error: samples on hull surfaces, by area.
		std::vector<std::pair<int, int>> tris;   // (hull, triangle)
		std::vector<double>              cum;
		double                           total = 0;
		for (int i = 0; i < (int) hulls.size(); ++i)
			for (int t = 0; t < (int) hulls[i].h.triangles.size(); ++t) {
				const auto& T = hulls[i].h.triangles[t];
				const auto& P = hulls[i].h.points;
				total += 0.5 * (P[T[1]] - P[T[0]]).cross(P[T[2]] - P[T[0]]).norm();
				tris.emplace_back(i, t);
				cum.push_back(total);
			}
		const double tol = 1e-5 * diag;   // shared cut faces of two hulls agree to rounding, not exactly
		std::optional<CGAL::Side_of_triangle_mesh<SMesh, K>> side;
		if (closed) side.emplace(tree);
		double       emax = 0, esum = 0, out_max = 0, in_max = 0;
		acd::Vec3    at = acd::Vec3::Zero();
		int          at_hull = -1;
		long         kept = 0;
		for (long s = 0; s < samples; ++s) {
			const size_t k = std::lower_bound(cum.begin(), cum.end(), U(rng) * total) - cum.begin();
			const auto [i, t] = tris[std::min(k, tris.size() - 1)];
			const auto& T = hulls[i].h.triangles[t];
			const auto& P = hulls[i].h.points;
			double a = U(rng), b = U(rng);
			if (a + b > 1) a = 1 - a, b = 1 - b;
			const acd::Vec3 x = P[T[0]] + a * (P[T[1]] - P[T[0]]) + b * (P[T[2]] - P[T[0]]);
			bool covered = false;
			for (int j = 0; j < (int) hulls.size() && !covered; ++j)
				covered = j != i && hulls[j].covers(x, tol);
			if (covered) continue;
			const K::Point_3 q(x.x(), x.y(), x.z());
			const double     d = std::sqrt(tree.squared_distance(q));
			if (d > emax) emax = d, at = x, at_hull = i;
			if (side) {
				double& m = (*side)(q) == CGAL::ON_BOUNDED_SIDE ? in_max : out_max;
				m         = std::max(m, d);
			}
			esum += d;
			++kept;
		}
		// Volume IoU by Monte Carlo in the common box.
		Eigen::AlignedBox3d box = ibox;
		for (const Hull& h : hulls) box.extend(h.box);
		long both = 0, either = 0;
		if (side) {
			for (long s = 0; s < samples; ++s) {
				const acd::Vec3 x = box.min() + box.sizes().cwiseProduct(acd::Vec3(U(rng), U(rng), U(rng)));
				const bool in_solid = (*side)(K::Point_3(x.x(), x.y(), x.z())) != CGAL::ON_UNBOUNDED_SIDE;
				bool       in_hulls = false;
				for (const Hull& h : hulls)
					if ((in_hulls = h.contains(x))) break;
				both += in_solid && in_hulls;
				either += in_solid || in_hulls;
			}
		}
		std::printf("{\"hulls\": %zu, \"degenerate_hulls\": %d, \"hull_error\": %.6g, \"hull_error_mean\": %.6g, "
		            "\"surface_samples\": %ld, \"hull_error_at\": [%.17g, %.17g, %.17g], \"hull_error_hull\": %d, ",
		            hulls.size(), degenerate, emax / diag, kept ? esum / kept / diag : 0.0, kept, at.x(), at.y(), at.z(), at_hull);
		if (side) std::printf("\"hull_error_outside\": %.6g, \"hull_error_inside\": %.6g, ", out_max / diag, in_max / diag);
		else std::printf("\"hull_error_outside\": null, \"hull_error_inside\": null, ");
		if (closed && either > 0) {
			const double p = double(both) / either;
			std::printf("\"iou\": %.6g, \"iou_stderr\": %.3g, \"volume_samples\": %ld}\n", p,
			            std::sqrt(p * (1 - p) / either), samples);
		}
		else std::printf("\"iou\": null, \"iou_stderr\": null, \"volume_samples\": 0}\n");
	}
	catch (const std::exception& e) {
		std::printf("{\"error\": \"%s\"}\n", e.what());
		return 1;
	}
}
