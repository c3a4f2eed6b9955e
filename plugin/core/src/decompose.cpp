#include "acd/decompose.h"
#include "acd/parallel.h"

#include <CGAL/Cartesian_d.h>
#include <CGAL/Min_sphere_of_points_d_traits_3.h>
#include <CGAL/Min_sphere_of_spheres_d.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <queue>
#include <sstream>

namespace acd {

double enclosing_diameter(const std::vector<Vec3>& pts)
{
	using K      = CGAL::Simple_cartesian<double>;
	using Traits = CGAL::Min_sphere_of_points_d_traits_3<K, double>;
	std::vector<K::Point_3> p;
	p.reserve(pts.size());
	for (const Vec3& v : pts) p.emplace_back(v.x(), v.y(), v.z());
	CGAL::Min_sphere_of_spheres_d<Traits> ms(p.begin(), p.end());
	return 2 * ms.radius();
}

namespace {

// What cutting a node needs from its measure; kept while the node waits to be cut.
struct Measured
{
	Topology        topo;
	ConvexHull      hull;
	ConcavityReport rep;
	explicit Measured(const TriMesh& m) : topo(m), hull(m.V), rep(measure_concavity(m, topo, hull)) {}
};

// A candidate cut's parts scored by the paper's measure itself (the same one the recursion uses).
double part_concavity(const TriMesh& m)
{
	return Measured(m).rep.max_concavity;
}

Plane through(const Vec3& p, Vec3 n)
{
	Plane pl;
	pl.n = n.normalized();
	pl.d = pl.n.dot(p);
	return pl;
}

} // namespace

std::vector<Plane> candidate_planes(const TriMesh& m, const Topology& topo, const ConvexHull& hull,
                                    const ConcavityReport& rep, CutPlaneSelection sel, int around)
{
	std::vector<Plane> out;
	const int          r = rep.max_vertex;
	if (r < 0) return out;
	const Vec3& p = m.V[r];

	// The notch's most reflex incident edge, and the bisector of its two faces' normals. Equally
	// reflex edges (a symmetric notch) are told apart by their midpoints in the part's frame.
	const PoseFrame& frame = rep.frame;
	double          best = -1;
	Vec3            edge = Vec3::Zero(), bis = Vec3::Zero(), mid = Vec3::Zero();
	for (int f = 0; f < (int) m.F.size(); ++f) {
		// Only faces around r matter; scanning is O(n) once per cut.
		int k = -1;
		for (int j = 0; j < 3; ++j)
			if (m.F[f][j] == r) k = j;
		if (k < 0) continue;
		for (int e : {k, (k + 2) % 3}) {   // the two edges of f at r
			const int g = topo.neighbour[f][e];
			if (g < f || !is_reflex(m, topo, f, e)) continue;
			const Vec3 a = m.V[m.F[f][e]], b = m.V[m.F[f][(e + 1) % 3]];
			auto normal = [&](int face) {
				const Tri& t = m.F[face];
				return (m.V[t[1]] - m.V[t[0]]).cross(m.V[t[2]] - m.V[t[0]]).normalized();
			};
			const Vec3   n1 = normal(f), n2 = normal(g);
			const double excess = (n1.cross(n2)).norm() * (b - a).norm();   // sharper and longer first
			const double tie    = 1e-9 * std::max(best, excess);
			if (excess > best + tie || (excess >= best - tie && frame.before((a + b) / 2, mid))) {
				best = excess;
				edge = (b - a).normalized();
				bis  = n1 + n2;
				mid  = (a + b) / 2;
			}
		}
	}
	if (best > 0 && bis.norm() > 1e-12) out.push_back(through(p, edge.cross(bis)));
	if (sel == CutPlaneSelection::Bisector && !out.empty()) return out;

	// Planes containing the retraction direction (the bridge's normal), at evenly spread angles
	// starting from the notch edge's direction; and the plane parallel to the bridge.
	if (rep.max_bridge >= 0) {
		const Vec3 nb = hull.facet_plane[rep.max_bridge].n;
		Vec3       u  = edge - nb * nb.dot(edge);
		if (u.norm() < 1e-9) u = nb.unitOrthogonal();
		u.normalize();
		const Vec3 w = nb.cross(u);
		for (int k = 0; k < around; ++k) {
			const double th = M_PI * k / around;
			out.push_back(through(p, std::cos(th) * u + std::sin(th) * w));
		}
		out.push_back(through(p, nb));
	}
	return out;
}

std::vector<int> Decomposition::leaves() const
{
	std::vector<int> l;
	for (int i = 0; i < (int) nodes.size(); ++i)
		if (nodes[i].leaf()) l.push_back(i);
	std::sort(l.begin(), l.end(), [&](int a, int b) { return nodes[a].path < nodes[b].path; });
	return l;
}

double Decomposition::max_leaf_concavity() const
{
	double c = 0;
	for (int i : leaves()) c = std::max(c, nodes[i].concavity);
	return c;
}

std::string Decomposition::to_json() const
{
	std::ostringstream o;
	o.precision(17);
	o << "{\"tau\":" << tau << ",\"max_parts_reached\":" << (max_parts_reached ? "true" : "false")
	  << ",\"nodes\":[";
	for (size_t i = 0; i < nodes.size(); ++i) {
		const Node& n = nodes[i];
		o << (i ? "," : "") << "{\"id\":" << i << ",\"path\":\"" << n.path << "\",\"parent\":" << n.parent
		  << ",\"children\":[" << n.child[0] << "," << n.child[1] << "]"
		  << ",\"concavity\":" << n.concavity << ",\"volume\":" << n.volume << ",\"notches\":" << n.notches
		  << ",\"leaf\":" << (n.leaf() ? "true" : "false") << ",\"uncut\":" << (n.uncut ? "true" : "false")
		  << ",\"solids\":" << (n.solids ? "true" : "false");
		if (n.concavity > 0)
			o << ",\"notch\":[" << n.notch.x() << "," << n.notch.y() << "," << n.notch.z() << "]";
		if (n.has_plane)
			o << ",\"plane\":{\"normal\":[" << n.plane.n.x() << "," << n.plane.n.y() << "," << n.plane.n.z()
			  << "],\"offset\":" << n.plane.d << "}";
		o << "}";
	}
	o << "]}";
	return o.str();
}

namespace {

Decomposition decompose_normalized(const Solid& solid, const DecomposeOptions& opt);

} // namespace

Decomposition decompose(const Solid& solid, const DecomposeOptions& opt)
{
	if (!(opt.tau > 0) || !std::isfinite(opt.tau))
		throw Error(Error::InvalidOption, "tau must be a positive, finite length.");
	if (opt.max_parts < 0) throw Error(Error::InvalidOption, "max_parts must be 0 (unbounded) or positive.");

	// Work centred and at unit size: a mesh far from the origin (CAD, map coordinates) would
	// otherwise carry rounding errors hundreds of times larger than the same mesh at the origin,
	// and rounding decides near-ties. The tree is mapped back to model coordinates at the end.
	Vec3 c = Vec3::Zero();
	for (const Vec3& p : solid.mesh.V) c += p;
	c /= (double) solid.mesh.V.size();
	const double s = extent(solid.mesh.V);
	Solid        unit = solid;
	for (Vec3& p : unit.mesh.V) p = (p - c) / s;
	unit.volume /= s * s * s;
	DecomposeOptions o = opt;
	o.tau /= s;
	Decomposition D = decompose_normalized(unit, o);
	D.tau = opt.tau;
	for (Node& n : D.nodes) {
		for (Vec3& p : n.mesh.V) p = p * s + c;
		n.concavity *= s;
		n.volume *= s * s * s;
		n.notch = n.notch * s + c;
		n.plane.d = n.plane.d * s + n.plane.n.dot(c);
	}
	return D;
}

namespace {

Decomposition decompose_normalized(const Solid& solid, const DecomposeOptions& opt)
{
	const auto start = std::chrono::steady_clock::now();

	Decomposition D;
	D.tau = opt.tau;

	// Nodes waiting to be cut keep their measure; others drop it.
	std::vector<std::unique_ptr<Measured>> measured;
	auto add_node = [&](TriMesh mesh, int parent, const std::string& path) {
		Node n;
		n.parent = parent;
		n.path   = path;
		n.mesh   = std::move(mesh);
		D.nodes.push_back(std::move(n));
		measured.emplace_back();
		return (int) D.nodes.size() - 1;
	};
	auto measure_node = [&](int id) {
		Node& n         = D.nodes[id];
		auto  ms        = std::make_unique<Measured>(n.mesh);
		n.concavity     = ms->rep.max_concavity;
		n.volume        = signed_volume(n.mesh);
		n.notches       = ms->rep.notches;
		if (ms->rep.max_vertex >= 0) n.notch = n.mesh.V[ms->rep.max_vertex];
		if (n.concavity > opt.tau) measured[id] = std::move(ms);
	};

	// Several solids (disjoint shells): no notch lies between them, so the measure would call the
	// union convex. Split them off first, one per level (A | rest), keeping the tree binary.
	std::vector<TriMesh> solids;
	if (solid.shells > 1) solids = connected_solids(solid.mesh);
	std::vector<int> first_open;
	if (solids.size() > 1) {
		int node = add_node(solid.mesh, -1, "0");
		for (size_t k = 0; k + 1 < solids.size(); ++k) {
			Node& n     = D.nodes[node];
			n.volume    = signed_volume(n.mesh);
			n.solids    = true;
			const std::string path = n.path;
			TriMesh rest;
			for (size_t j = k + 1; j < solids.size(); ++j) append(rest, solids[j]);
			const int a = add_node(std::move(solids[k]), node, path + '0');
			const int b = add_node(k + 2 < solids.size() ? std::move(rest) : std::move(solids[k + 1]), node, path + '1');
			D.nodes[node].child[0] = a;
			D.nodes[node].child[1] = b;
			first_open.push_back(a);
			if (k + 2 == solids.size()) first_open.push_back(b);
			node = b;
		}
	}
	else first_open.push_back(add_node(solid.mesh, -1, "0"));
	double c0 = opt.tau;
	for (int id : first_open) {
		measure_node(id);
		c0 = std::max(c0, D.nodes[id].concavity);
	}

	// Open nodes, most concave first (ties by path), so a max_parts bound cuts the worst notches.
	auto worse = [&](int a, int b) {
		if (D.nodes[a].concavity != D.nodes[b].concavity) return D.nodes[a].concavity < D.nodes[b].concavity;
		return D.nodes[a].path > D.nodes[b].path;
	};
	std::priority_queue<int, std::vector<int>, decltype(worse)> open(worse);
	for (int id : first_open) open.push(id);
	int parts = (int) first_open.size();
	while (!open.empty()) {
		const int id = open.top();
		if (D.nodes[id].concavity <= opt.tau) break;   // every open node is within tau
		if (opt.max_parts > 0 && parts >= opt.max_parts) {
			D.max_parts_reached = true;
			break;
		}
		if (opt.time_limit_seconds > 0 &&
		    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > opt.time_limit_seconds) {
			D.time_limit_reached = true;
			break;
		}
		open.pop();
		// A cut that keeps failing to lower the concavity must not recurse forever.
		if (D.nodes[id].path.size() > 96) {
			D.nodes[id].uncut = true;
			measured[id].reset();
			continue;
		}
		if (opt.progress) {
			const double cur = D.nodes[id].concavity;
			int pct = (int) (100 * std::log(c0 / cur) / std::max(1e-12, std::log(c0 / opt.tau)));
			char msg[96];
			std::snprintf(msg, sizeof msg, "Decomposing: %d parts, worst concavity %.4g", parts, cur);
			if (!opt.progress(std::clamp(pct, 0, 99), msg))
				throw Error(Error::Cancelled, "The decomposition was cancelled.");
		}

		const TriMesh&  mesh = D.nodes[id].mesh;
		const Measured& ms   = *measured[id];
		std::vector<Plane> planes = candidate_planes(mesh, ms.topo, ms.hull, ms.rep, opt.cut_plane_selection,
		                                             opt.candidate_planes);
		if (opt.cut_plane_selection == CutPlaneSelection::Bisector && planes.size() == 1) {
			// Fall back to the other candidates only if the bisector cannot split.
			auto more = candidate_planes(mesh, ms.topo, ms.hull, ms.rep, CutPlaneSelection::Best, opt.candidate_planes);
			planes.insert(planes.end(), more.begin() + std::min<size_t>(1, more.size()), more.end());
		}
		const Vec3 notch = mesh.V[ms.rep.max_vertex];

		// Split and score every candidate plane; candidates are independent, so use all cores.
		struct Trial
		{
			SplitOutcome so;
			bool         ok = false;
			double       score = 0, sum = 0;
		};
		std::vector<Trial> trials(planes.size());
		const double       v0 = D.nodes[id].volume;
		auto               run_trial = [&](size_t i) {
            Trial& t = trials[i];
            if (!separate(mesh, planes[i], notch, t.so)) return;
            // A plane that grazes the part shaves off a sliver and resolves nothing.
            if (signed_volume(t.so.parts[0]) < 1e-5 * v0 || signed_volume(t.so.parts[1]) < 1e-5 * v0) return;
            if (opt.cut_plane_selection == CutPlaneSelection::Bisector) {
                t.ok = true;
                return;
            }
            try {
                const double a = part_concavity(t.so.parts[0]), b = part_concavity(t.so.parts[1]);
                t.score = std::max(a, b);
                t.sum   = a + b;
                t.ok    = true;
            }
            catch (const Error&) {   // a part with no volume
            }
		};
		if (opt.cut_plane_selection == CutPlaneSelection::Bisector) {
			// The paper's plane first; the others only if it cannot split.
			for (size_t i = 0; i < planes.size(); ++i) {
				run_trial(i);
				if (trials[i].ok) break;
			}
		}
		else parallel_for(planes.size(), run_trial);

		// The paper's bisector plane (candidate 0) stands unless another leaves clearly (10%) less
		// concavity: greedy scores alone would rather shave small arms off one by one. Among the
		// others, scores within a hair (planes are nudged ~1e-7 of the size off vertices) are ties,
		// settled by the total concavity.
		const double hair = 1e-6 * extent(mesh.V);
		int          pick = -1;
		for (int i = 0; i < (int) trials.size(); ++i) {
			const Trial& t = trials[i];
			if (!t.ok) continue;
			if (pick < 0 || t.score < trials[pick].score - hair ||
			    (t.score <= trials[pick].score + hair && t.sum < trials[pick].sum - hair))
				pick = i;
		}
		if (pick > 0 && trials[0].ok && !(trials[pick].score < 0.9 * trials[0].score)) pick = 0;
		const bool   found = pick >= 0;
		SplitOutcome best;
		if (found) best = std::move(trials[pick].so);
		measured[id].reset();
		if (!found) {
			D.nodes[id].uncut = true;   // stays a leaf; reported
			continue;
		}
		D.nodes[id].has_plane = true;
		D.nodes[id].plane     = best.plane;
		const std::string path = D.nodes[id].path;
		for (int s = 0; s < 2; ++s) {
			const int c          = add_node(std::move(best.parts[s]), id, path + char('0' + s));
			D.nodes[id].child[s] = c;   // after add_node: it may move D.nodes
		}
		// The two halves are independent: measure them on two cores.
		parallel_for(2, [&](size_t s) { measure_node(D.nodes[id].child[s]); });
		for (int s = 0; s < 2; ++s) open.push(D.nodes[id].child[s]);
		++parts;
		if (std::getenv("ACD_DEBUG"))
			std::fprintf(stderr, "cut %s conc %.4g notch (%.3f %.3f %.3f) n (%.3f %.3f %.3f) -> %.4g %.4g (faces %zu %zu)\n",
			             path.c_str(), D.nodes[id].concavity, notch.x(), notch.y(), notch.z(), best.plane.n.x(),
			             best.plane.n.y(), best.plane.n.z(), D.nodes[D.nodes[id].child[0]].concavity,
			             D.nodes[D.nodes[id].child[1]].concavity, D.nodes[D.nodes[id].child[0]].mesh.F.size(),
			             D.nodes[D.nodes[id].child[1]].mesh.F.size());
	}
	if (opt.progress) opt.progress(100, "Decomposition done");
	return D;
}

} // namespace

} // namespace acd
