/****************************************************************************
* meshlab-acd: approximate convex decomposition for MeshLab                  *
* GPL-3.0-or-later, like MeshLab.                                            *
****************************************************************************/
// The filters' work: read parameters, convert meshes, call the core (acd::), add layers, log.

#include "filter_acd.h"
#include "meshlab_convert.h"
#include "parameters.h"

#include <acd/decompose3/decompose.h>
#include <acd/structure/level_of_detail.h>
#include <acd/hull/hull_union.h>
#include <acd/polygon/polygon.h>
#include <acd/structure/skeleton.h>
#include <acd/io/tree_io.h>
#include <acd/structure/collision_hulls.h>
#include <acd/decompose3/decompose_mesh.h>
#include <acd/mesh/measures.h>
#include <acd/solid/solid.h>

#include <vcg/complex/algorithms/update/color.h>

#include <QFile>

#include <algorithm>
#include <array>
#include <chrono>
#include <fstream>
#include <optional>
#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif


namespace {

QString self_intersection_message(long n)
{
	return QString("The mesh intersects itself (%1 pairs of faces cross away from shared corners). Repair it "
	               "with preprocessing = alpha_wrap or MeshLab's 'Alpha Wrap', or find the faces with 'Select "
	               "Self Intersecting Faces'.").arg(n);
}

// Bytes the decomposition needs per input face at most (measured: 631 MB for 1.07M faces in
// bisector mode, including pymeshlab's own copy; best mode keeps more candidates alive).
constexpr double kBytesPerFace = 1500;

// Memory the system can still give us (Linux: MemAvailable; other POSIX systems: free pages), 0 if
// unknown (Windows): the check is then skipped.
double available_memory()
{
#if defined(__linux__)
	std::ifstream meminfo("/proc/meminfo");
	std::string   key;
	double        kb = 0;
	std::string   unit;
	while (meminfo >> key >> kb >> unit)
		if (key == "MemAvailable:") return kb * 1024;
#endif
#if defined(_SC_AVPHYS_PAGES) && defined(_SC_PAGE_SIZE)
	const long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
	return pages > 0 && page > 0 ? double(pages) * double(page) : 0;
#else
	return 0;
#endif
}

vcg::Color4b part_color(int i)
{
	// Golden-angle hues: neighbouring parts get clearly different colours.
	float h = std::fmod(0.13f + 0.61803398875f * i, 1.0f);
	vcg::Color4b c;
	c.SetHSVColor(h, 0.65f, 0.95f);
	return c;
}

// A new layer holding `m` (with `edges`, e.g. a polygon's outline), placed like `like` when given, in
// part colour `colour` (< 0: left uncoloured).
MeshModel* add_layer(MeshDocument& md, const QString& name, const acd::TriMesh& m, const MeshModel* like, int colour,
                     const std::vector<std::array<int, 2>>& edges = {})
{
	MeshModel* layer = md.addNewMesh("", name, false);
	acdml::from_trimesh(m, layer->cm, edges);
	if (like) layer->cm.Tr = like->cm.Tr;
	if (colour >= 0) {
		layer->updateDataMask(MeshModel::MM_VERTCOLOR);
		vcg::tri::UpdateColor<CMeshO>::PerVertexConstant(layer->cm, part_color(colour));
	}
	layer->updateBoxAndNormals();
	return layer;
}

QString layer_name(const char* prefix, const std::string& path) { return QString(prefix) + QString::fromStdString(path); }

// The tree's JSON (made only when a file is asked for) into `path`; nothing when it is empty.
template <class Json> void write_tree_file(const QString& path, Json json)
{
	if (path.isEmpty()) return;
	QFile f(path);
	if (!f.open(QIODevice::WriteOnly | QIODevice::Truncate)) throw MLException("Cannot write the tree file " + path);
	f.write(QByteArray::fromStdString(json()));
}

// A 2D piece lifted into its plane: triangles (none when its loops touch: `whole` false) and the
// outline's edges, numbered as triangulate() numbers the loops' points.
acd::TriMesh piece_mesh(const acd::Polygon2& piece, const acd::PlanarLoops& pl, std::vector<std::array<int, 2>>& outline,
                        bool& whole)
{
	std::vector<acd::Vec2> V2;
	acd::TriMesh           t;
	whole = acd::triangulate(piece, V2, t.F);
	for (const acd::Vec2& q : V2) t.V.push_back(pl.lift(q));
	int base = 0;
	for (int l = 0; l <= (int) piece.holes.size(); ++l) {
		const int n = (int) (l == 0 ? piece.outer.size() : piece.holes[l - 1].size());
		for (int i = 0; i < n; ++i) outline.push_back({base + i, base + (i + 1) % n});
		base += n;
	}
	return t;
}

} // namespace

std::map<std::string, QVariant> FilterACD::notchConcavity(MeshModel& mm, vcg::CallBackPos* cb)
{
	if (cb) cb(0, "Measuring notch concavity...");
	acd::Solid      s = acd::make_solid(acdml::to_trimesh(mm.cm));
	acd::Topology   topo(s.mesh);
	acd::ConvexHull hull(s.mesh.V);
	if (cb) cb(30, "Measuring notch concavity...");
	acd::ConcavityReport r = acd::measure_concavity(s.mesh, topo, hull);
	if (s.flipped) log("The mesh was oriented inward; concavity is measured on it turned outward.");
	if (s.self_intersections > 0) log("Warning: %s", qUtf8Printable(self_intersection_message(s.self_intersections)));

	// Back to MeshLab's vertices: split copies of a non-manifold vertex keep the largest value.
	mm.updateDataMask(MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR);
	std::vector<int> live;
	for (size_t i = 0; i < mm.cm.vert.size(); ++i)
		if (!mm.cm.vert[i].IsD()) live.push_back((int) i);
	for (int i : live) mm.cm.vert[i].Q() = 0;
	for (size_t v = 0; v < s.mesh.V.size(); ++v) {
		auto& q = mm.cm.vert[live[s.source_vertex[v]]].Q();
		q       = std::max<Scalarm>(q, (Scalarm) r.vertex_concavity[v]);
	}
	vcg::tri::UpdateColor<CMeshO>::PerVertexQualityRamp(mm.cm);

	const acd::Vec3 at = r.max_vertex >= 0 ? s.mesh.V[r.max_vertex] : acd::Vec3::Zero();
	log("Notch concavity: %d notches, %d bridges, %d pockets; max concavity %g at (%g, %g, %g)",
	    r.notches, r.bridges, r.pockets, r.max_concavity, at.x(), at.y(), at.z());
	if (cb) cb(100, "Done");
	return {
		{"notches", r.notches},
		{"bridges", r.bridges},
		{"pockets", r.pockets},
		{"patches", r.patches},
		{"max_concavity", r.max_concavity},
		{"hull_distance", r.hull_reach},
		{"max_concavity_position", QVariant::fromValue(Point3m(at.x(), at.y(), at.z()))},
		{"max_concavity_x", at.x()},
		{"max_concavity_y", at.y()},
		{"max_concavity_z", at.z()},
		{"has_notch", r.max_vertex >= 0},
	};
}

// What cutting the hulls down to a budget cost, and the bound they then hold.
void FilterACD::log_budget(const acd::CollisionHulls& ch, double hull_distance)
{
	const acd::HullBudget& b = ch.budget;
	log("%d of %zu hulls cut down to %s's budget (vertices %d, polygons %d, triangles %d; 0 = no limit) by keeping "
	    "as many of their facet planes as fit: each still contains its part and reaches at most %g beyond its exact "
	    "hull, so the hulls lie within %g of their parts",
	    ch.reduced, ch.hulls.size(), acd::engine(ch.engine).label, b.vertices, b.polygons, b.triangles, ch.max_reach,
	    hull_distance + ch.max_reach);
	if (ch.over_budget > 0) log("Warning: %d hulls are still over the budget", ch.over_budget);
	if (ch.thin_count > 0)
		log("Warning: %d hulls are thinner than 1/100 of their extent: %s runs them on the CPU", ch.thin_count,
		    acd::engine(ch.engine).label);
}


FilterACD::Run FilterACD::runDecomposition(const RichParameterList& par, MeshModel& input, vcg::CallBackPos* cb)
{
	acd::TriMesh raw   = acdml::to_trimesh(input.cm);
	const double avail = available_memory();
	if (avail > 0 && kBytesPerFace * raw.F.size() > avail)
		throw MLException(QString("The mesh has %1 faces; decomposing it needs about %2 MB, but only %3 MB are "
		                          "available. Simplify it first (e.g. 'Simplification: Quadric Edge Collapse "
		                          "Decimation') or free memory.")
		                      .arg(raw.F.size())
		                      .arg(kBytesPerFace * raw.F.size() / 1e6, 0, 'f', 0)
		                      .arg(avail / 1e6, 0, 'f', 0));
	const acd::PrepareOptions prep = acdml::prepare_options(par);
	if (cb && prep.mode != acd::Preprocessing::None)
		cb(0, prep.mode == acd::Preprocessing::AlphaWrap ? "Alpha wrapping the input..." : "Checking the input (as given, welded, holes filled or wrapped)...");
	// tau may be a share of the size: the prepared solid's (the last one prepared is the one decomposed).
	double                 size = 0;
	acd::MeshDecomposition md   = acd::decompose_mesh(raw, prep, [&](const acd::PreparedSolid& p) {
		log_prepared(p);
		size = acd::enclosing_diameter(p.solid.mesh.V);
		return acdml::decompose_options(par, size, cb);
	});
	if (!md.fallback.empty()) log("Decomposed as given, %s: alpha wrapped instead.", md.fallback.c_str());
	return {std::move(md.prepared), md.options, size, std::move(md.d), md.fallback};
}

void FilterACD::log_prepared(const acd::PreparedSolid& p)
{
	const acd::Solid& s = p.solid;
	if (p.done == acd::PreparedSolid::Welded)
		log("Not decomposable as given (%s) Welding %d vertices within 1e-5 of its size made it a valid solid; it is "
		    "decomposed welded, not wrapped.", p.reason.c_str(), p.welded);
	if (p.done == acd::PreparedSolid::Filled)
		log("Not decomposable as given (%s) Its %d holes were filled (%d on the planes their rims run on, the rest "
		    "faired: the patches continue its surface); it is decomposed filled, not wrapped. The patches reach %g from "
		    "the input.", p.reason.c_str(), p.filled, p.on_planes, p.to_input);
	if (p.done == acd::PreparedSolid::Wrapped && !p.reason.empty())
		log("Not decomposable as given (%s) It is alpha wrapped: %d wrap(s), alpha %g%% kept, holding %.0f%% of the "
		    "input's interior.", p.reason.c_str(), p.tries, p.alpha / p.size * 100, 100 * p.inside);
	if (p.done == acd::PreparedSolid::Wrapped)
		log("Alpha wrap: %zu faces in, %zu out; the wrap lies about %g outside the input (alpha %g); measured at "
		    "vertices, it reaches %g from the input and the input %g from it%s", p.faces_in, s.mesh.F.size(), p.offset,
		    p.alpha, p.to_input, p.from_input,
		    p.capped ? ". Its openings were capped where the input's winding number is 1/2."
		    : p.skin ? ". The input encloses no solid: the wrap is a thin skin about it." : "");
	if (s.self_intersections > 0) log("Warning: %s", qUtf8Printable(self_intersection_message(s.self_intersections)));
	if (s.reoriented_shells > 0)
		log("%d of %d shells were oriented against their nesting (outer shells outward, cavities inward) and "
		    "were turned.", s.reoriented_shells, s.shells);
	else if (s.flipped) log("The mesh was oriented inward; the decomposition uses it turned outward.");
	if (s.cavities > 0) log("The solid has %d cavities (closed inner shells).", s.cavities);
	if (s.unreferenced_vertices > 0) log("%d unreferenced vertices were ignored.", s.unreferenced_vertices);
	if (s.split_vertices > 0) log("%d non-manifold vertices were split into one copy per fan.", s.split_vertices);
}

std::map<std::string, QVariant>
FilterACD::decompose(const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb)
{
	const auto          t0    = std::chrono::steady_clock::now();
	MeshModel&          input = *md.mm();
	Run                 run   = runDecomposition(par, input, cb);
	const acd::Solid&   s     = run.prepared.solid;
	const auto&         o     = run.options;
	const double        size  = run.size;
	acd::Decomposition& d     = run.d;

	const auto engine = acdml::hull_engine(par);
	const bool hulls  = par.getBool("output_hulls") || engine != acd::Engine::None;
	const acd::CollisionHulls ch = hulls ? acd::collision_hulls(d, engine, par.getInt("max_hull_vertices")) : acd::CollisionHulls{};
	int idx = 0;
	for (int li : d.parts()) {
		const acd::Node& n = d.nodes[li];
		add_layer(md, layer_name("acd_", n.path), n.mesh, &input, idx);
		if (hulls) add_layer(md, layer_name("acd_hull_", n.path), ch.hulls[idx].mesh, &input, idx);
		++idx;
	}
	write_tree_file(par.getString("tree_file"), [&] { return acd::tree_to_json(d, true, hulls ? &ch : nullptr); });
	if (ch.reduced > 0) log_budget(ch, d.max_hull_distance());
	const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	const int    uncut = (int) std::count_if(d.nodes.begin(), d.nodes.end(), [](const acd::Node& n) { return n.uncut; });
	log("Approximate convex decomposition: %d parts, tau %g (model units), max part concavity %g, farthest "
	    "hull %g from its part, %.2f s%s",
	    idx, o.tau, d.max_part_concavity(), d.max_hull_distance(), secs,
	    d.max_parts_reached ? " (max_parts reached: some parts exceed tau)" : "");
	const std::vector<int> parts   = d.parts();
	const int              by_hull = (int) std::count_if(parts.begin(), parts.end(), [&](int i) { return d.nodes[i].hull_certified; });
	if (d.merges > 0) log("%d neighbouring parts merged after the cuts (their unions within tau)", d.merges);
	if (by_hull > 0)
		log("%d parts are within tau by their hulls, with notches up to %.3g tau deep below them "
		    "(merge_measure = concavity keeps every notch within tau)", by_hull, d.max_part_concavity() / o.tau);
	if (d.pick_rule == acd::PickRule::PartsNeeded)
		log("The cuts picked by the parts their halves need left fewer parts than those picked by the worse half");
	if (d.proxy_searches > 0)
		log("Searched on a %d-face copy %g from the surface; every part certified on the mesh itself (%d searched again)",
		    d.proxy_faces, d.proxy_distance, d.proxy_retries);
	if (d.merge_time_limit_reached)
		log("Merging stopped at the time limit after %d merges: the parts are within tau, but more of them could merge "
		    "(raise time_limit or set it to 0)", d.merges);
	if (uncut > 0) log("Warning: %d parts above tau could not be cut by any candidate plane", uncut);
	if (d.films_dropped > 0)
		log("%d zero-thickness films (volume %g) no plane could split were dropped from parts", d.films_dropped,
		    d.film_volume);
	if (d.kept_cavities > 0)
		log("Warning: %d cavities were kept inside parts (keep_cavities); those parts are not tau-convex.",
		    d.kept_cavities);
	return {
		{"parts", idx},
		{"tau", o.tau},
		{"tau_model_units", o.tau},
		{"size", size},
		{"max_concavity", d.max_part_concavity()},
		{"root_concavity", d.nodes[0].concavity},
		{"time", secs},
		{"max_parts_reached", d.max_parts_reached},
		{"time_limit_reached", d.time_limit_reached},
		{"uncut_parts", uncut},
		{"films_dropped", d.films_dropped},
		{"merges", d.merges},
		{"hull_certified_parts", by_hull},   // within tau by their hulls alone (merge_measure)
		{"cuts_by_parts_needed", d.pick_rule == acd::PickRule::PartsNeeded},   // cut_search kept its second tree
		{"merge_time_limit_reached", d.merge_time_limit_reached},
		{"tree_nodes", (int) d.nodes.size()},
		{"alpha_wrapped", run.prepared.done == acd::PreparedSolid::Wrapped},
		{"wrap_alpha_used", run.prepared.done == acd::PreparedSolid::Wrapped ? 100 * run.prepared.alpha_share : 0.0},
		{"welded_vertices", run.prepared.welded},
		{"preprocessing_done", (int) run.prepared.done},   // 0 as given, 1 welded, 2 alpha wrapped, 3 holes filled
		{"holes_filled", run.prepared.filled},
		{"holes_on_planes", run.prepared.on_planes},   // of them, closed on the planes their rims run on
		{"self_crossing_wrapped", !run.fallback.empty()},
		{"wrap_capped", run.prepared.capped},   // openings closed along the input's winding-number level set
		{"wrap_skin", run.prepared.skin},       // the input encloses no solid: the wrap is a skin about it
		{"wrap_cap_share", run.prepared.cap_share},   // share of that level set spanning openings
		{"preprocessing_time", run.prepared.seconds},
		{"solid_to_input", run.prepared.to_input},     // model units, sampled on the solid's faces
		{"input_to_solid", run.prepared.from_input},   // and at the input's
		{"not_as_given_code", run.prepared.reason_code},   // why not as given: acd::Error::Code (0: it was)
		{"not_as_given_count", (int) run.prepared.reason_count},
		{"self_intersections", (int) s.self_intersections},
		{"cavities", s.cavities},
		{"hole_cuts", d.hole_cuts},
		{"kept_cavities", d.kept_cavities},
		{"max_hull_distance", d.max_hull_distance()},
		{"tau_convex", d.tau_convex()},
		{"proxy_faces", d.proxy_faces},       // the search's simplified copy (0: searched on the mesh itself)
		{"proxy_distance", d.proxy_distance},
		{"proxy_retries", d.proxy_retries},   // parts whose certificate failed on the mesh, searched again
		{"hulls_reduced", ch.reduced},          // hulls cut down to the engine's budget
		{"hull_reach", ch.max_reach},           // farthest a reduced hull reaches beyond its exact hull
		{"hulls_over_budget", ch.over_budget},
		{"hulls_thin", ch.thin_count},          // the engine would refuse them (PhysX GPU: in-sphere < extent / 100)
		// What the collision hulls then hold: each within this of its part (exact hulls: the hull distance).
		{"collision_hull_distance", d.max_hull_distance() + ch.max_reach},
	};
}

std::map<std::string, QVariant> FilterACD::skeleton(const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb)
{
	const auto      t0    = std::chrono::steady_clock::now();
	MeshModel&      input = *md.mm();
	const Run       run   = runDecomposition(par, input, cb);
	acd::SkeletonOptions so;
	so.max_refinement = par.getInt("max_refinement");
	so.off_centre     = par.getFloat("off_centre");
	if (so.max_refinement < 0 || !(so.off_centre > 0)) throw MLException("max_refinement must be >= 0 and off_centre > 0.");
	if (cb) cb(99, "Extracting the skeleton...");
	const acd::Skeleton sk = acd::skeleton(run.d, so);
	MeshModel*          layer = md.addNewMesh("", "acd_skeleton", false);
	CMeshO&             m     = layer->cm;
	auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(m, sk.V.size());
	for (const auto& p : sk.V) (vi++)->P() = CMeshO::CoordType(p.x(), p.y(), p.z());
	auto ei = vcg::tri::Allocator<CMeshO>::AddEdges(m, sk.E.size());
	for (const auto& e : sk.E) {
		ei->V(0) = &m.vert[e[0]];
		ei->V(1) = &m.vert[e[1]];
		++ei;
	}
	m.Tr = input.cm.Tr;
	layer->updateDataMask(MeshModel::MM_VERTCOLOR);
	for (size_t i = 0; i < sk.V.size(); ++i)
		m.vert[i].C() = sk.piece[i] < 0 ? vcg::Color4b(vcg::Color4b::White) : part_color(sk.piece[i]);
	layer->updateBoxAndNormals();
	const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	const int    comps = sk.components();
	log("Skeleton: %d vertices, %d edges, %d components, from %d parts (%d refinement splits), %.2f s",
	    (int) sk.V.size(), (int) sk.E.size(), comps, (int) run.d.leaves().size(), sk.refined, secs);
	return {
		{"vertices", (int) sk.V.size()},
		{"edges", (int) sk.E.size()},
		{"components", comps},
		{"parts", (int) run.d.leaves().size()},
		{"pieces", sk.pieces},
		{"refinements", sk.refined},
		{"time", secs},
	};
}

std::map<std::string, QVariant> FilterACD::hullUnion(const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb)
{
	const auto t0    = std::chrono::steady_clock::now();
	MeshModel& input = *md.mm();
	const Run  run   = runDecomposition(par, input, cb);
	const auto engine = acdml::hull_engine(par);
	const acd::CollisionHulls ch = acd::collision_hulls(run.d, engine, par.getInt("max_hull_vertices"));
	std::vector<acd::TriMesh> hulls;
	int                       idx = 0;
	for (int li : run.d.parts()) {
		add_layer(md, layer_name("acd_hull_", run.d.nodes[li].path), ch.hulls[idx].mesh, &input, idx);
		hulls.push_back(ch.hulls[idx++].mesh);
	}
	if (ch.reduced > 0) log_budget(ch, run.d.max_hull_distance());
	const bool boolean = par.getEnum("merge") == 1;
	if (cb) cb(99, boolean ? "Boolean union of the hulls..." : "Merging the hulls...");
	const acd::TriMesh merged = acd::merge_hulls(hulls, boolean);
	add_layer(md, "acd_hull_union", merged, &input, -1);
	const int samples = par.getInt("iou_samples");
	double    se      = 0;
	const double iou  = samples > 0 ? acd::volume_iou(run.prepared.solid.mesh, hulls, samples, 1, &se) : 0;
	const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	const double reduction = merged.F.empty() ? 0 : double(run.prepared.solid.mesh.F.size()) / double(merged.F.size());
	log("Hull union: %d hulls, %zu faces merged (%s) from %zu input faces (%.1fx fewer), volume IoU %.4f +- %.4f, %.2f s",
	    idx, merged.F.size(), boolean ? "boolean union" : "together", run.prepared.solid.mesh.F.size(), reduction, iou, se, secs);
	return {
		{"hulls", idx},
		{"input_faces", (int) run.prepared.solid.mesh.F.size()},
		{"union_faces", (int) merged.F.size()},
		{"face_reduction", reduction},
		{"volume_iou", iou},
		{"volume_iou_stderr", se},
		{"boolean_union", boolean},
		{"time", secs},
	};
}

namespace {

// The tree written with tree_file, back into the core's structure (leaf meshes; hulls kept aside by
// node id).
acd::Decomposition read_tree(const QString& path, std::vector<acd::TriMesh>& hulls)
{
	QFile f(path);
	if (path.isEmpty() || !f.open(QIODevice::ReadOnly)) throw MLException("Cannot read the tree file '" + path + "'.");
	return acd::tree_from_json(f.readAll().toStdString(), &hulls);
}

} // namespace

std::map<std::string, QVariant> FilterACD::levelOfDetail(const RichParameterList& par, MeshDocument& md,
                                                         vcg::CallBackPos* cb)
{
	const auto                t0 = std::chrono::steady_clock::now();
	std::vector<acd::TriMesh> hulls;
	if (cb) cb(0, "Reading the tree...");
	const acd::Decomposition D = read_tree(par.getString("tree_file"), hulls);
	const bool               by_depth = par.getEnum("level_by") == 1;
	double                   tau      = par.getFloat("tau");
	if (!by_depth) {
		const bool no_hull = hulls[0].V.empty();
		tau                = acdml::tau_in_model_units(par, no_hull ? 0.0 : acd::enclosing_diameter(hulls[0].V));
		if (no_hull) throw MLException("The tree file has no root hull (write it with tree_file).");
	}
	const int depth = par.getInt("depth");
	if (by_depth && depth < 0) throw MLException("depth must be 0 (the root) or more.");
	if (cb && !by_depth) cb(2, "Checking the coarser parts' hulls...");
	const std::vector<int> level = by_depth ? acd::level_of_detail(D, tau, depth) : acd::level_of_detail_within(D, tau, hulls);
	double                 worst = 0;
	int                    idx = 0, open_parts = 0;
	for (int id : level) {
		if (cb) cb(5 + 90 * idx / (int) level.size(), "Rebuilding parts...");
		const acd::Node&   n = D.nodes[id];
		const acd::TriMesh m = acd::rebuild_solid(D, id);
		worst                = std::max(worst, n.concavity);
		try {
			acd::make_solid(m);
		}
		catch (const acd::Error&) {
			++open_parts;
		}
		add_layer(md, layer_name("acd_", n.path), m, nullptr, idx);
		if (par.getBool("output_hulls") && !hulls[id].F.empty()) add_layer(md, layer_name("acd_hull_", n.path), hulls[id], nullptr, idx);
		++idx;
	}
	const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	log("Level of detail: %d parts of the saved %d (%s), max part concavity %g, %.2f s, nothing recomputed",
	    idx, (int) D.parts().size(), by_depth ? qUtf8Printable(QString("depth %1").arg(depth))
	                                           : qUtf8Printable(QString("tau %1").arg(tau)),
	    worst, secs);
	if (open_parts > 0) log("Warning: %d rebuilt parts are not closed.", open_parts);
	return {
		{"parts", idx},
		{"tree_parts", (int) D.parts().size()},
		{"tau_model_units", by_depth ? D.tau : tau},
		{"max_concavity", worst},
		{"open_parts", open_parts},
		{"time", secs},
	};
}

std::map<std::string, QVariant>
FilterACD::decomposePolygon(const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb)
{
	const auto                     t0    = std::chrono::steady_clock::now();
	MeshModel&                     input = *md.mm();
	std::vector<std::array<int, 2>> edges;
	const acd::TriMesh              raw = acdml::to_trimesh(input.cm, nullptr, &edges);
	const acd::PlanarLoops          pl  = acd::planar_loops(raw.V, raw.F, edges);
	const std::vector<acd::Polygon2> polys = acd::polygons_from_loops(pl.loops);

	std::vector<acd::Vec3> pts;
	for (const auto& P : polys)
		for (const auto& q : P.outer) pts.push_back(pl.lift(q));
	const double size = acd::enclosing_diameter(pts);
	acd::PolygonOptions o = acdml::polygon_options(par, size);

	int         pieces = 0, holes = 0, notches = 0, hole_cuts = 0, kept = 0;
	double      max_conc = 0, root_conc = 0;
	bool        max_reached = false;
	std::vector<acd::Decomposition2> trees;
	for (size_t k = 0; k < polys.size(); ++k) {
		if (cb) {
			// Each polygon's own progress, scaled into its share of the whole.
			const int lo = (int) (100 * k / polys.size()), span = std::max<int>(1, 100 / (int) polys.size());
			o.progress = [cb, lo, span](int pct, const char* msg) { return cb(lo + pct * span / 100, msg); };
		}
		const acd::Decomposition2 d = acd::decompose(polys[k], o);
		trees.push_back(d);
		holes += (int) polys[k].holes.size();
		notches += d.nodes[0].notch_count;
		hole_cuts += d.hole_cuts;
		kept += d.kept_holes;
		max_reached |= d.max_parts_reached;
		root_conc = std::max(root_conc, d.nodes[0].concavity);
		max_conc  = std::max(max_conc, d.max_leaf_concavity());
		for (int li : d.leaves()) {
			std::vector<std::array<int, 2>> outline;
			bool                            whole = true;
			const acd::TriMesh t = piece_mesh(d.nodes[li].polygon, pl, outline, whole);
			if (!whole)
				log("Warning: piece %s could not be triangulated (its loops touch); only its outline is added.",
				    d.nodes[li].path.c_str());
			const QString name = polys.size() > 1 ? QString("acd_p%1_%2").arg(k).arg(QString::fromStdString(d.nodes[li].path))
			                                       : QString("acd_%1").arg(QString::fromStdString(d.nodes[li].path));
			add_layer(md, name, t, &input, pieces, outline);
			++pieces;
		}
	}
	write_tree_file(par.getString("tree_file"), [&] { return acd::polygon_trees_to_json(trees); });
	const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	log("Polygon convex decomposition: %d polygons, %d holes, %d notches; %d pieces, tau %g (model units), max "
	    "piece concavity %g, %.3f s%s",
	    (int) polys.size(), holes, notches, pieces, o.tau, max_conc, secs,
	    max_reached ? " (max_parts reached: some pieces exceed tau)" : "");
	if (kept > 0) log("Warning: %d holes were kept inside pieces (keep_cavities); those pieces are not tau-convex.", kept);
	return {
		{"parts", pieces},
		{"polygons", (int) polys.size()},
		{"holes", holes},
		{"notches", notches},
		{"tau", o.tau},
		{"tau_model_units", o.tau},
		{"size", size},
		{"max_concavity", max_conc},
		{"root_concavity", root_conc},
		{"time", secs},
		{"max_parts_reached", max_reached},
		{"hole_cuts", hole_cuts},
		{"kept_holes", kept},
		{"tau_convex", kept == 0 && max_conc <= o.tau},
		{"plane_normal_x", pl.n.x()},
		{"plane_normal_y", pl.n.y()},
		{"plane_normal_z", pl.n.z()},
	};
}
