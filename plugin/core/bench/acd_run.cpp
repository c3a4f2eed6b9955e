// Decompose an OBJ file from the command line (for profiling the core without MeshLab):
//   acd_run mesh.obj [tau_percent] [CUT_PLANE_SELECTION][+merge] [max_parts]
// Defaults and labels come from the options table (acd/api/options.h); the mesh is taken as given unless
// ACD_RUN_WRAP=alpha_percent, which prepares it as preprocessing = auto does (welded or wrapped), at
// ACD_RUN_OFFSET=percent (the table's wrap_offset unless given).
#include "acd/api/options.h"
#include "acd/decompose3/decompose_mesh.h"
#include "acd/mesh/measures.h"
#include "acd/solid/solid.h"
#include "obj_io.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>

// The parts that break the certificate, for diagnosis; with ACD_RUN_TRACE, each one's ancestors: how
// each cut above it split them.
static void diagnose(const acd::Decomposition& d)
{
	for (int i : d.parts()) {
		const acd::Node& n = d.nodes[i];
		if (d.certified(i)) continue;
		std::printf("  part %s: concavity %.4g tau, hull %.4g..%.4g tau, uncut %d, faces %zu\n", n.path.c_str(),
		            n.concavity / d.tau, n.hull_distance / d.tau, n.hull_distance_bound / d.tau, n.uncut, n.mesh.F.size());
		if (!std::getenv("ACD_RUN_TRACE")) continue;
		for (const acd::Node& a : d.nodes)
			if (a.has_plane && n.path.rfind(a.path, 0) == 0) {
				const acd::Node& kept = d.nodes[a.child[n.path[a.path.size()] - '0']];
				const acd::Node& off  = d.nodes[a.child['1' - n.path[a.path.size()]]];
				std::printf("    depth %3zu: concavity %.4g tau -> kept %.4g tau (volume %.4g), off %.4g tau (volume %.3g)\n",
				            a.path.size(), a.concavity / d.tau, kept.concavity / d.tau, kept.volume / a.volume,
				            off.concavity / d.tau, off.volume / a.volume);
			}
	}
}

// With ACD_RUN_TREE, every cut: where it was made, the plane, and how it split the node.
static void print_cuts(const acd::Decomposition& d)
{
	for (const acd::Node& a : d.nodes) {
		if (!a.has_plane) continue;
		const acd::Node& c0 = d.nodes[a.child[0]];
		const acd::Node& c1 = d.nodes[a.child[1]];
		std::printf("  cut %-12s concavity %.3g tau at (%.4g %.4g %.4g), n (%.3f %.3f %.3f) -> %.3g tau (%.3g), %.3g tau (%.3g)\n",
		            a.path.c_str(), a.concavity / d.tau, a.notch.x(), a.notch.y(), a.notch.z(), a.plane.n.x(),
		            a.plane.n.y(), a.plane.n.z(), c0.concavity / d.tau, c0.volume / a.volume, c1.concavity / d.tau,
		            c1.volume / a.volume);
	}
}

int main(int argc, char** argv)
{
	const acd::Option& cuts = acd::option("cut_plane_selection");
	if (argc < 2) {
		std::fprintf(stderr, "usage: %s mesh.obj [tau_percent] [%s][+merge] [max_parts]\n", argv[0], cuts.labels().c_str());
		return 2;
	}
	acd::TriMesh m = acd::bench::read_obj(argv[1]);
	try {
		auto              t0  = std::chrono::steady_clock::now();
		const std::string sel = argc > 3 ? argv[3] : "";
		acd::PrepareOptions prep;
		prep.mode = acd::Preprocessing::None;
		if (const char* a = std::getenv("ACD_RUN_WRAP")) {   // preprocessing auto: alpha a% of size
			const char* o = std::getenv("ACD_RUN_OFFSET");
			prep.mode     = acd::Preprocessing::Auto;
			prep.alpha    = std::atof(a) / 100;
			prep.offset   = (o ? std::atof(o) : acd::option("wrap_offset").value) / 100;
		}
		const acd::MeshDecomposition md = acd::decompose_mesh(m, prep, [&](const acd::PreparedSolid& p) {
			if (p.done != acd::PreparedSolid::AsGiven)
				std::printf("%s: %zu faces in %.3f s\n", acd::describe(p).c_str(), p.solid.mesh.F.size(),
				            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
			acd::DecomposeOptions o;
			const double tau = argc > 2 ? std::atof(argv[2]) : acd::option("tau").value;
			o.tau            = tau / 100 * acd::enclosing_diameter(p.solid.mesh.V);
			const int chosen = cuts.value_of(sel.substr(0, sel.find('+')));
			o.cut_plane_selection = acd::CutPlaneSelection(chosen >= 0 ? chosen : (int) cuts.value);
			o.merge_parts         = sel.empty() ? acd::option("merge_parts").value != 0 : sel.find("+merge") != std::string::npos;
			if (argc > 4) o.max_parts = std::atoi(argv[4]);
			o.progress = [](int p, const char* msg) {
				std::fprintf(stderr, "%3d%% %s\n", p, msg);
				return true;
			};
			return o;
		});
		const acd::Decomposition& d = md.d;
		double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
		std::printf("faces %zu  tau %.6g  parts %zu  max concavity %.6g  time %.3f s\n", md.prepared.solid.mesh.F.size(), md.options.tau,
		            d.parts().size(), d.max_part_concavity(), secs);
		std::printf("tau_convex %d  max hull distance %.6g  merges %d  time limit %d\n", d.tau_convex(),
		            d.max_hull_distance(), d.merges, d.time_limit_reached);
		if (d.proxy_searches > 0)
			std::printf("proxy: %d faces, %.3g tau from the solid; %d searches, %d parts searched again\n", d.proxy_faces,
			            d.proxy_distance / d.tau, d.proxy_searches, d.proxy_retries);
		if (std::getenv("ACD_RUN_TREE")) print_cuts(d);
		diagnose(d);
		if (const char* node = std::getenv("ACD_RUN_NODE"))   // one node of the tree, by its path
			for (const acd::Node& n : d.nodes)
				if (n.path == node) acd::bench::write_obj_objects(std::string(node) + ".obj", {n.mesh});
		if (const char* dump = std::getenv("ACD_RUN_PARTS"))   // every part, one object each
			acd::bench::write_obj_objects(dump, [&] {
				std::vector<acd::TriMesh> parts;
				for (int i : d.parts()) parts.push_back(d.nodes[i].mesh);
				return parts;
			}());
	}
	catch (const std::exception& e) {
		std::printf("error: %s\n", e.what());
		return 1;
	}
}
