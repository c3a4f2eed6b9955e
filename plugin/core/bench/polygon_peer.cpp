// 2D benchmark driver: our polygon decomposition at several tau values beside CGAL's Partition_2
// (optimal_convex_partition_2, approx_convex_partition_2, greene_approx_convex_partition_2) on the
// same polygon, one JSON line per method. Reads the acd2d .poly format (see pymeshlab_acd/polygon_io.py).
#include <acd/polygon/polygon.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Partition_traits_2.h>
#include <CGAL/partition_2.h>
#include <CGAL/partition_is_valid_2.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <list>
#include <sstream>
#include <string>

namespace {

// Chains of a .poly file: "count", then per chain "n out|in", n points, and an index line.
std::vector<acd::Loop2> read_poly(const char* path)
{
	std::ifstream     in(path);
	std::stringstream clean;
	std::string       line;
	while (std::getline(in, line)) clean << line.substr(0, line.find('#')) << '\n';
	int n = 0;
	if (!(clean >> n) || n <= 0) throw std::runtime_error("not a .poly file");
	std::vector<acd::Loop2> loops(n);
	for (auto& L : loops) {
		int         m = 0;
		std::string kind;
		clean >> m >> kind;
		std::vector<acd::Vec2> pts(m);
		for (auto& p : pts) clean >> p.x() >> p.y();
		for (int i = 0; i < m; ++i) {
			int k = 0;
			clean >> k;
			L.push_back(pts.at(k - 1));
		}
		if (!clean) throw std::runtime_error("truncated .poly file");
	}
	return loops;
}

double seconds_since(std::chrono::steady_clock::time_point t0)
{
	return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace

int main(int argc, char** argv)
{
	if (argc < 3) {
		std::fprintf(stderr, "usage: %s polygon.poly tau[,tau...] [optimal_max_vertices]\n", argv[0]);
		return 2;
	}
	try {
		const auto polys = acd::polygons_from_loops(read_poly(argv[1]));
		const acd::Polygon2& P = polys.at(0);
		const int optimal_max = argc > 3 ? std::atoi(argv[3]) : 120;
		std::printf("{\"method\":\"input\",\"vertices\":%zu,\"holes\":%zu,\"notches\":%d}\n", P.outer.size(),
		            P.holes.size(), acd::measure_concavity(P).notches);
		std::stringstream taus(argv[2]);
		std::string       tok;
		while (std::getline(taus, tok, ',')) {
			for (auto sel : {acd::CutLineSelection::Bisector, acd::CutLineSelection::Best}) {
				acd::PolygonOptions o;
				o.tau                = std::atof(tok.c_str());
				o.cut_line_selection = sel;
				const auto t0 = std::chrono::steady_clock::now();
				const auto D  = acd::decompose(P, o);
				std::printf("{\"method\":\"ours_%s\",\"tau\":%s,\"parts\":%zu,\"seconds\":%.6f}\n",
				            sel == acd::CutLineSelection::Best ? "best" : "bisector", tok.c_str(), D.leaves().size(),
				            seconds_since(t0));
			}
		}
		if (!P.holes.empty()) return 0;   // Partition_2 takes simple polygons only
		using K      = CGAL::Exact_predicates_inexact_constructions_kernel;
		using Traits = CGAL::Partition_traits_2<K>;
		std::list<Traits::Point_2> pts;
		for (const auto& p : P.outer) pts.emplace_back(p.x(), p.y());
		auto run = [&](const char* name, auto fn) {
			std::list<Traits::Polygon_2> out;
			const auto t0 = std::chrono::steady_clock::now();
			fn(pts.begin(), pts.end(), std::back_inserter(out));
			const double secs = seconds_since(t0);
			// CGAL's own check: the pieces are convex and tile the polygon.
			const bool valid = CGAL::convex_partition_is_valid_2(pts.begin(), pts.end(), out.begin(), out.end());
			std::printf("{\"method\":\"%s\",\"parts\":%zu,\"seconds\":%.6f,\"valid\":%s}\n", name, out.size(), secs,
			            valid ? "true" : "false");
		};
		run("cgal_approx", [](auto a, auto b, auto o) { CGAL::approx_convex_partition_2(a, b, o); });
		run("cgal_greene", [](auto a, auto b, auto o) { CGAL::greene_approx_convex_partition_2(a, b, o); });
		if ((int) P.outer.size() <= optimal_max)
			run("cgal_optimal", [](auto a, auto b, auto o) { CGAL::optimal_convex_partition_2(a, b, o); });
	}
	catch (const std::exception& e) {
		std::fprintf(stderr, "error: %s\n", e.what());
		return 1;
	}
	return 0;
}
