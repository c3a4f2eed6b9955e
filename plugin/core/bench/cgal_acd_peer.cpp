// Peer for the benchmark: CGAL 6.2's voxel-based approximate_convex_decomposition() (V-HACD-like).
//   cgal_acd_peer input.obj hulls_out.obj max_hulls
// Prints "hulls N time S peak_kb K" (time: the decomposition alone; K: this process's peak
// resident set, VmHWM).
#include "obj_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/approximate_convex_decomposition.h>

#include <chrono>
#include <fstream>
#include <string>
#include <cstdio>

int main(int argc, char** argv)
{
	if (argc < 4) {
		std::fprintf(stderr, "usage: %s input.obj hulls_out.obj max_hulls\n", argv[0]);
		return 2;
	}
	using K     = CGAL::Exact_predicates_inexact_constructions_kernel;
	using SMesh = CGAL::Surface_mesh<K::Point_3>;
	try {
		const acd::TriMesh m = acd::bench::read_obj(argv[1]);
		SMesh              sm;
		std::vector<SMesh::Vertex_index> vs;
		for (const acd::Vec3& p : m.V) vs.push_back(sm.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
		for (const acd::Tri& t : m.F) sm.add_face(vs[t[0]], vs[t[1]], vs[t[2]]);
		using Volume = std::pair<std::vector<K::Point_3>, std::vector<std::array<unsigned int, 3>>>;
		std::vector<Volume> out;
		const auto          t0 = std::chrono::steady_clock::now();
		CGAL::approximate_convex_decomposition(
		    sm, std::back_inserter(out),
		    CGAL::parameters::maximum_number_of_convex_volumes(std::atoi(argv[3])).concurrency_tag(CGAL::Parallel_if_available_tag()));
		const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
		std::vector<acd::TriMesh> hulls;
		for (const Volume& v : out) {
			acd::TriMesh h;
			for (const auto& p : v.first) h.V.emplace_back(p.x(), p.y(), p.z());
			for (const auto& t : v.second) h.F.push_back({(int) t[0], (int) t[1], (int) t[2]});
			hulls.push_back(std::move(h));
		}
		acd::bench::write_obj_objects(argv[2], hulls);
		long          peak_kb = 0;
		std::ifstream status("/proc/self/status");
		for (std::string line; std::getline(status, line);)
			if (line.rfind("VmHWM:", 0) == 0) peak_kb = std::atol(line.c_str() + 6);
		std::printf("hulls %zu time %.4f peak_kb %ld\n", hulls.size(), secs, peak_kb);
	}
	catch (const std::exception& e) {
		std::printf("error: %s\n", e.what());
		return 1;
	}
}
