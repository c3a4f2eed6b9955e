#include "acd/io/tree_io.h"
#include "acd/hull/hull.h"
#include "acd/mesh/parallel.h"

#include <nlohmann/json.hpp>

namespace acd {

namespace {

using json = nlohmann::json;

json mesh_json(const TriMesh& m)
{
	json v = json::array(), f = json::array();
	for (const Vec3& p : m.V) v.insert(v.end(), {p.x(), p.y(), p.z()});
	for (const Tri& t : m.F) f.insert(f.end(), {t[0], t[1], t[2]});
	return {{"v", v}, {"f", f}};
}

[[noreturn]] void bad(const std::string& what) { throw Error(Error::InvalidInput, "The tree file " + what); }

TriMesh mesh_from(const json& o)
{
	TriMesh m;
	const json &v = o.at("v"), &f = o.at("f");
	for (size_t i = 0; i + 2 < v.size(); i += 3) m.V.emplace_back(v[i].get<double>(), v[i + 1].get<double>(), v[i + 2].get<double>());
	for (size_t i = 0; i + 2 < f.size(); i += 3) {
		const Tri t{f[i].get<int>(), f[i + 1].get<int>(), f[i + 2].get<int>()};
		for (int k : t)
			if (k < 0 || k >= (int) m.V.size()) bad("has a face with a bad vertex index.");
		m.F.push_back(t);
	}
	return m;
}

// Each node's hull as a mesh (geometry trees). A leaf's and a merged part's from its mesh, in parallel; a cut
// node's from its children's hull vertices: its parts hold its every point, so the hull is the hull of
// theirs, built from a few hundred points instead of every vertex of a large solid.
std::vector<TriMesh> node_hulls(const Decomposition& D)
{
	const auto direct = [&](size_t i) {
		try {
			return ConvexHull(D.nodes[i].mesh.V).mesh();
		} catch (const Error&) {   // a node spanning no volume has no hull
			return TriMesh();
		}
	};
	std::vector<TriMesh> hull(D.nodes.size());
	parallel_for(D.nodes.size(), [&](size_t i) {
		const Node& n = D.nodes[i];
		if ((n.child[0] < 0 || !n.merged.empty()) && !n.mesh.F.empty()) hull[i] = direct(i);
	});
	for (size_t i = D.nodes.size(); i-- > 0;) {   // children come after their parent
		const Node& n = D.nodes[i];
		if (n.child[0] < 0 || !n.merged.empty() || n.mesh.F.empty()) continue;
		const TriMesh &a = hull[n.child[0]], &b = hull[n.child[1]];
		if (a.V.empty() || b.V.empty()) {
			hull[i] = direct(i);
			continue;
		}
		std::vector<Vec3> points = a.V;
		points.insert(points.end(), b.V.begin(), b.V.end());
		hull[i] = ConvexHull(points).mesh();
	}
	return hull;
}

json node_json(const Node& n, int id, bool geometry, const TriMesh& hull)
{
	json o = {{"id", id},
	          {"path", n.path},
	          {"parent", n.parent},
	          {"children", {n.child[0], n.child[1]}},
	          {"concavity", n.concavity},
	          {"hull_distance", n.hull_distance},
	          {"hull_distance_bound", n.hull_distance_bound},
	          {"volume", n.volume},
	          {"notches", n.notch_count},
	          {"leaf", n.leaf()},
	          {"uncut", n.uncut},
	          {"solids", n.solids},
	          {"cavities", n.cavities},
	          {"hole_cut", n.hole_cut}};
	if (n.concavity > 0) o["notch"] = {n.notch.x(), n.notch.y(), n.notch.z()};
	if (n.has_plane) o["plane"] = {{"normal", {n.plane.n.x(), n.plane.n.y(), n.plane.n.z()}}, {"offset", n.plane.d}};
	if (!n.merged.empty()) o["merged"] = n.merged;
	if (n.hull_certified) o["hull_certified"] = true;   // within tau by its hull, its notches deeper
	if (n.part >= 0) o["part"] = n.part;
	if (geometry && !n.mesh.F.empty()) {
		if (!hull.F.empty()) o["hull"] = mesh_json(hull);
		if (n.leaf() || !n.merged.empty()) o["mesh"] = mesh_json(n.mesh);
	}
	return o;
}

json node2_json(const Node2& n, int id)
{
	json o = {{"id", id},
	          {"path", n.path},
	          {"parent", n.parent},
	          {"children", {n.child[0], n.child[1]}},
	          {"concavity", n.concavity},
	          {"area", n.area},
	          {"notches", n.notch_count},
	          {"holes", n.hole_count},
	          {"leaf", n.leaf()},
	          {"uncut", n.uncut},
	          {"hole_cut", n.hole_cut}};
	if (n.has_cut)
		o["cut"] = {{"from", {n.cut_from.x(), n.cut_from.y()}},
		            {"to", {n.cut_to.x(), n.cut_to.y()}},
		            {"normal", {n.line.n.x(), n.line.n.y()}},
		            {"offset", n.line.d}};
	return o;
}

} // namespace

static json hulls_json(const CollisionHulls& c)
{
	json hulls = json::array();
	for (size_t i = 0; i < c.hulls.size(); ++i) {
		const BoundedHull& h = c.hulls[i];
		hulls.push_back({{"node", c.nodes[i]}, {"vertices", h.vertices}, {"polygons", h.polygons},
		                 {"triangles", h.triangles}, {"polygon_vertices", h.polygon_vertices}, {"reach", h.reach},
		                 {"reduced", h.reduced}, {"within_budget", h.within_budget},
		                 {"inscribed_radius", h.inscribed_radius}, {"extent", h.extent}, {"thin", (bool) c.thin[i]}});
	}
	return {{"engine", engine(c.engine).label},
	        {"budget", {{"vertices", c.budget.vertices}, {"polygons", c.budget.polygons},
	                    {"triangles", c.budget.triangles}, {"polygon_vertices", c.budget.polygon_vertices}}},
	        {"max_reach", c.max_reach},
	        {"hulls", hulls}};
}

std::string tree_to_json(const Decomposition& D, bool geometry, const CollisionHulls* hulls)
{
	json                       nodes = json::array();
	const std::vector<TriMesh> hull  = geometry ? node_hulls(D) : std::vector<TriMesh>(D.nodes.size());
	for (size_t i = 0; i < D.nodes.size(); ++i) nodes.push_back(node_json(D.nodes[i], (int) i, geometry, hull[i]));
	json root = {{"schema", kTreeSchema},
	                   {"dimension", 3},
	                   {"tau", D.tau},
	                   {"max_parts_reached", D.max_parts_reached},
	                   {"hole_cuts", D.hole_cuts},
	                   {"kept_cavities", D.kept_cavities},
	                   {"films_dropped", D.films_dropped},
	                   {"merges", D.merges},
	                   {"nodes", nodes}};
	if (hulls) root["collision"] = hulls_json(*hulls);
	return root.dump();
}

Decomposition tree_from_json(const std::string& text, std::vector<TriMesh>* hulls)
{
	const json root = json::parse(text, nullptr, false);
	if (root.is_discarded() || !root.is_object()) bad("is not valid JSON.");
	if (root.value("schema", 0) > kTreeSchema) bad("was written by a newer meshlab-acd (schema " + std::to_string(root.value("schema", 0)) + ").");
	if (!root.contains("nodes") || !root["nodes"].is_array() || root["nodes"].empty())
		bad("has no nodes (was it written by the 3D decomposition?).");
	const json&   nodes = root["nodes"];
	Decomposition D;
	try {
		D.tau           = root.value("tau", 0.0);
		D.kept_cavities = root.value("kept_cavities", 0);
		D.merges        = root.value("merges", 0);
		if (hulls) hulls->assign(nodes.size(), TriMesh());
		const int count = (int) nodes.size();
		for (int i = 0; i < count; ++i) {
			const json& o = nodes[i];
			Node        n;
			n.parent    = o.value("parent", -1);
			n.child[0]  = o.at("children").at(0).get<int>();
			n.child[1]  = o.at("children").at(1).get<int>();
			n.path      = o.value("path", std::string());
			n.concavity = o.value("concavity", 0.0);
			n.volume    = o.value("volume", 0.0);
			n.solids    = o.value("solids", false);
			n.cavities  = o.value("cavities", 0);
			for (int c : n.child)
				if (c >= count || (c < 0 && n.child[0] != n.child[1])) bad("has broken links.");
			if (o.contains("plane")) {
				const json& nn = o["plane"].at("normal");
				n.has_plane    = true;
				n.plane.n      = Vec3(nn.at(0).get<double>(), nn.at(1).get<double>(), nn.at(2).get<double>());
				n.plane.d      = o["plane"].at("offset").get<double>();
			}
			if (o.contains("merged")) n.merged = o["merged"].get<std::vector<int>>();
			n.hull_certified = o.value("hull_certified", false);
			n.part = o.value("part", -1);
			for (int l : n.merged)
				if (l < 0 || l >= count) bad("has broken links.");
			if (n.part >= count) bad("has broken links.");
			if (n.leaf() || !n.merged.empty()) {
				if (!o.contains("mesh")) bad("has no part geometry (write it with tree_file).");
				n.mesh = mesh_from(o["mesh"]);
			}
			if (hulls && o.contains("hull")) (*hulls)[i] = mesh_from(o["hull"]);
			D.nodes.push_back(std::move(n));
		}
	}
	catch (const json::exception& e) {
		bad(std::string("is malformed: ") + e.what());
	}
	return D;
}

std::string polygon_trees_to_json(const std::vector<Decomposition2>& trees)
{
	json polygons = json::array();
	for (const Decomposition2& d : trees) {
		json nodes = json::array();
		for (size_t i = 0; i < d.nodes.size(); ++i) nodes.push_back(node2_json(d.nodes[i], (int) i));
		polygons.push_back({{"dimension", 2},
		                    {"tau", d.tau},
		                    {"max_parts_reached", d.max_parts_reached},
		                    {"hole_cuts", d.hole_cuts},
		                    {"kept_holes", d.kept_holes},
		                    {"nodes", nodes}});
	}
	return json({{"schema", kTreeSchema}, {"dimension", 2}, {"polygons", polygons}}).dump();
}

} // namespace acd
