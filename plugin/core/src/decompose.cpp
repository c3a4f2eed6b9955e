#include "acd/decompose.h"
#include "acd/hull_reach.h"
#include "acd/merge.h"
#include "acd/parallel.h"
#include "recursion.h"

#include <Eigen/Eigenvalues>

#include <CGAL/Cartesian_d.h>
#include <CGAL/Min_sphere_of_points_d_traits_3.h>
#include <CGAL/Min_sphere_of_spheres_d.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <queue>
#include <set>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

namespace acd {

// The recursion's hole count of a 3D node: its cavities.
int holes_in(const Node& n)
{
	return n.cavities;
}

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

// The faces of each cavity (a shell of negative volume) of a solid.
std::vector<std::vector<int>> cavity_faces(const TriMesh& m)
{
	int                           n = 0;
	const std::vector<int>        comp = face_components(m, &n);
	std::vector<std::vector<int>> shell(n);
	for (int f = 0; f < (int) m.F.size(); ++f) shell[comp[f]].push_back(f);
	std::vector<std::vector<int>> out;
	if (n < 2) return out;
	for (auto& faces : shell) {
		TriMesh sh;
		sh.V = m.V;
		for (int f : faces) sh.F.push_back(m.F[f]);
		if (signed_volume(sh) < 0) out.push_back(std::move(faces));
	}
	return out;
}

// The solid without its cavities (the same vertex array; unused vertices are harmless to the hull
// only if dropped, so they are).
TriMesh outer_surface(const TriMesh& m, const std::vector<std::vector<int>>& cavities)
{
	std::vector<char> drop(m.F.size(), 0);
	for (const auto& c : cavities)
		for (int f : c) drop[f] = 1;
	TriMesh          out;
	std::vector<int> id(m.V.size(), -1);
	for (int f = 0; f < (int) m.F.size(); ++f) {
		if (drop[f]) continue;
		Tri t;
		for (int k = 0; k < 3; ++k) {
			int& i = id[m.F[f][k]];
			if (i < 0) {
				i = (int) out.V.size();
				out.V.push_back(m.V[m.F[f][k]]);
			}
			t[k] = i;
		}
		out.F.push_back(t);
	}
	return out;
}

// What cutting a node needs from its measure; kept while the node waits to be cut. With
// keep_cavities only the outer surface is measured (a cavity never retracts to the hull).
struct Measured
{
	std::vector<std::vector<int>> cavities;   // faces of each cavity of the node's mesh
	TriMesh                       outer;      // keep_cavities with cavities: the measured surface
	Topology                      topo;
	ConvexHull                    hull;
	ConcavityReport               rep;
	Measured(const TriMesh& m, bool keep_cavities, double tau)
	    : cavities(cavity_faces(m)),
	      outer(keep_cavities && !cavities.empty() ? outer_surface(m, cavities) : TriMesh()),
	      topo(surface(m)), hull(surface(m).V), rep(measure_concavity(surface(m), topo, hull, tau))
	{
	}
	// What topo, hull and rep describe: the node's mesh `m` itself, or its outer surface. (The node's
	// mesh is passed in, not kept: nodes move when the tree grows.)
	const TriMesh& surface(const TriMesh& m) const { return outer.F.empty() ? m : outer; }
};

Plane through(const Vec3& p, Vec3 n)
{
	Plane pl;
	pl.n = n.normalized();
	pl.d = pl.n.dot(p);
	return pl;
}

// The way out of the pocket at p: towards the nearest point of the hull. The bridge facet's normal
// would do on a clean mesh, but a noisy pocket is lidded by many small facets, and which one is the
// bridge (so its normal) jumps; the nearest point moves with the surface. None when p lies on the
// hull (a prism's inner corner at its end face).
std::optional<Vec3> retraction(const ConvexHull& hull, const Vec3& p)
{
	Vec3         q;
	const double d = hull.distance_to_boundary(p, nullptr, -1, &q);
	if (!(d > 1e-9)) return std::nullopt;
	return Vec3((q - p) / d);
}

} // namespace

std::vector<Plane> cavity_planes(const TriMesh& m, const std::vector<int>& faces, const ConvexHull& hull,
                                 HoleHandling handling, int around, Vec3& centre)
{
	// Area-weighted moments of the cavity's surface: its vertices alone would follow the sampling.
	const SurfaceMoments mo = surface_moments(m, Vec3::Zero(), &faces);
	std::vector<Plane>   out;
	if (!(mo.area > 0)) return out;
	const Vec3 c = mo.centroid;
	centre       = c;
	const Eigen::Matrix3d cov = mo.second / mo.area - c * c.transpose();
	Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);   // eigenvalues ascending
	// The principal plane contains the two major axes: its normal is the minor axis.
	for (int k = 0; k < 3; ++k) {
		if (handling != HoleHandling::BestPlane && k > 0) break;
		out.push_back(through(c, es.eigenvectors().col(k)));
	}
	if (handling == HoleHandling::BestPlane) {
		// Planes containing the way out: from the centre towards the nearest hull facet.
		int        tri = -1;
		hull.distance_to_boundary(c, &tri);
		const Vec3 up = tri >= 0 ? hull.facet_plane[hull.triangle_facet[tri]].n : es.eigenvectors().col(0);
		// angles start from the cavity's major axis, so the fan turns with the object
		Vec3 u = es.eigenvectors().col(2) - up * up.dot(es.eigenvectors().col(2));
		if (u.norm() < 1e-9) u = es.eigenvectors().col(1) - up * up.dot(es.eigenvectors().col(1));
		u.normalize();
		const Vec3 w = up.cross(u);
		for (int k = 0; k < around; ++k) {
			const double th = M_PI * k / around;
			out.push_back(through(c, std::cos(th) * u + std::sin(th) * w));
		}
	}
	return out;
}

// The notch's most reflex incident edge (sharper and longer first) and its two faces' normals.
struct NotchEdge
{
	double              excess = -1;   // > 0 if the notch has a reflex edge
	Vec3                dir = Vec3::Zero(), along = Vec3::Zero(), mid = Vec3::Zero(), bis = Vec3::Zero();
	std::array<Vec3, 2> faces{Vec3::Zero(), Vec3::Zero()};
	bool                sharp() const { return excess > 0 && faces[0].cross(faces[1]).norm() >= 0.5; }
	bool                bisects() const { return excess > 0 && bis.norm() > 1e-12; }
};

// Equally reflex edges (a symmetric notch) are told apart by their midpoints in the part's frame.
NotchEdge notch_edge(const TriMesh& m, const Topology& topo, int r, const PoseFrame& frame)
{
	const Vec3& p = m.V[r];
	NotchEdge   ne;
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
			const double excess = (n1.cross(n2)).norm() * (b - a).norm();
			const double tie    = 1e-9 * std::max(ne.excess, excess);
			if (excess > ne.excess + tie || (excess >= ne.excess - tie && frame.before((a + b) / 2, ne.mid))) {
				ne.excess = excess;
				ne.dir    = (b - a).normalized();
				ne.along  = ((a - p).norm() > (b - p).norm() ? a - p : b - p).normalized();
				ne.bis    = n1 + n2;
				ne.mid    = (a + b) / 2;
				ne.faces  = {n1, n2};
			}
		}
	}
	return ne;
}

// The plane of the rim the notch edge belongs to: a groove, step or flange of a faceted solid of
// revolution is cut off whole, where the bisector or a facet's plane would take one wedge of it.
std::optional<Vec3> rim_normal(const TriMesh& m, const Topology& topo, int r, const NotchEdge& ne)
{
	std::vector<Vec3> pts;
	for (int v : reflex_chain(m, topo, r, ne.along, 0.7)) pts.push_back(m.V[v]);
	return chain_plane_normal(pts);
}

// The floor the notch rises from: of the notch edge's two faces, the one facing the bridge, if its
// plane holds a tenth of the surface or more. A shallow boss or ramp on a plate meets the plate at a
// flat angle, where the bisector slices across both; the plate's own face takes the boss off whole.
// A smooth or wrapped surface has no such flat, so it adds no plane to score there.
std::optional<Vec3> floor_normal(const TriMesh& m, const Vec3& p, const NotchEdge& ne, const Vec3& bridge)
{
	const Vec3   n     = ne.faces[0].dot(bridge) >= ne.faces[1].dot(bridge) ? ne.faces[0] : ne.faces[1];
	const Plane  floor = through(p, n);
	const double eps   = 1e-6 * extent(m.V);
	double       on = 0, all = 0;
	for (const Tri& t : m.F) {
		const Vec3   c    = (m.V[t[1]] - m.V[t[0]]).cross(m.V[t[2]] - m.V[t[0]]);
		const double area = c.norm();
		all += area;
		if (area > 0 && c.dot(n) > (1 - 1e-9) * area && floor.holds(m.V, t, eps)) on += area;
	}
	return on >= 0.1 * all ? std::optional<Vec3>(n) : std::nullopt;
}

// Planes through p at evenly spread angles about an axis, starting from normal n0 (at right angles
// to it); `from` skips the first ones.
void fan(std::vector<Plane>& out, const Vec3& p, const Vec3& n0, const Vec3& w, int around, int from = 0)
{
	for (int k = from; k < around; ++k) {
		const double th = M_PI * k / around;
		out.push_back(through(p, std::cos(th) * n0 + std::sin(th) * w));
	}
}

std::vector<Plane> candidate_planes(const TriMesh& m, const Topology& topo, const ConvexHull& hull,
                                    const ConcavityReport& rep, CutPlaneSelection sel, int around,
                                    CutPlaneSelection* used)
{
	if (used) *used = sel;
	std::vector<Plane> out;
	const int          r = rep.max_vertex;
	if (r < 0) return out;
	const Vec3&      p  = m.V[r];
	const NotchEdge  ne = notch_edge(m, topo, r, rep.frame);
	if (sel != CutPlaneSelection::MinSection && ne.bisects()) out.push_back(through(p, ne.dir.cross(ne.bis)));
	// The notch's two faces extended: a CAD step, slot or flange is cut off along its own face. Only
	// at a sharp reflex edge (30 degrees or more from flat): on a smooth or wrapped surface the faces'
	// planes are near-tangent slices.
	const bool                sharp = ne.sharp();
	const std::optional<Vec3> rim   = ne.excess > 0 && sel != CutPlaneSelection::MinSection && sel != CutPlaneSelection::Bisector
	                                      ? rim_normal(m, topo, r, ne) : std::nullopt;
	const std::optional<Vec3> floor = sel == CutPlaneSelection::BisectorOrFace && !sharp && !rim && ne.excess > 0 &&
	                                          !rep.reach_cut && rep.max_bridge >= 0
	                                      ? floor_normal(m, p, ne, hull.facet_plane[rep.max_bridge].n) : std::nullopt;
	if (sel == CutPlaneSelection::BisectorOrFace && !((sharp || rim || floor) && !out.empty())) sel = CutPlaneSelection::Bisector;
	if (used) *used = sel;
	if (sel == CutPlaneSelection::Bisector && !out.empty()) return out;
	std::array<Vec3, 2> faces = ne.faces;
	if (sel == CutPlaneSelection::BisectorOrFace) {
		// After the bisector, in the part's frame's order: a tie goes the same way in any pose.
		if (rep.frame.before(p + faces[1], p + faces[0])) std::swap(faces[0], faces[1]);
		if (sharp) out = {out[0], through(p, faces[0]), through(p, faces[1])};
		if (rim) out.push_back(through(p, *rim));
		if (floor) out.push_back(through(p, *floor));
		return out;
	}
	if (sel == CutPlaneSelection::Best && sharp)
		for (const Vec3& n : faces) out.push_back(through(p, n));
	if (sel == CutPlaneSelection::Best && rim) out.push_back(through(p, *rim));

	// Planes containing the retraction direction (the bridge's normal), at evenly spread angles
	// starting from the notch edge's direction; and the plane parallel to the bridge. A notch charged
	// with its bridge's reach: which of equally far bridges holds the farthest point is the search's
	// rounding, so the fan turns about the notch edge instead.
	if (rep.reach_cut && sel != CutPlaneSelection::MinSection && ne.bisects()) {
		const Vec3 n0 = ne.dir.cross(ne.bis).normalized();
		fan(out, p, n0, ne.dir.cross(n0), around, 1);
	}
	else if (rep.max_bridge >= 0) {
		const std::optional<Vec3> out_dir = sel == CutPlaneSelection::MinSection ? retraction(hull, p) : std::nullopt;
		const Vec3                nb      = out_dir ? *out_dir : hull.facet_plane[rep.max_bridge].n;
		Vec3       u  = ne.dir - nb * nb.dot(ne.dir);
		if (u.norm() < 1e-9) u = nb.unitOrthogonal();
		u.normalize();
		fan(out, p, u, nb.cross(u), around);
		if (sel != CutPlaneSelection::MinSection) out.push_back(through(p, nb));
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

std::vector<int> Decomposition::parts() const
{
	std::vector<int> p;
	for (int i = 0; i < (int) nodes.size(); ++i)
		if ((nodes[i].leaf() && nodes[i].part < 0) || !nodes[i].merged.empty()) p.push_back(i);
	std::sort(p.begin(), p.end(), [&](int a, int b) { return nodes[a].path < nodes[b].path; });
	return p;
}

double Decomposition::max_part_concavity() const
{
	double c = 0;
	for (int i : parts()) c = std::max(c, nodes[i].concavity);
	return c;
}

double Decomposition::max_hull_distance() const
{
	double c = 0;
	for (int i : parts()) c = std::max(c, nodes[i].hull_distance);
	return c;
}

bool Decomposition::certified(int id) const
{
	return acd::certified(nodes[id], tau);
}

bool Decomposition::tau_convex() const
{
	for (int i : parts())
		if (!certified(i)) return false;
	return kept_cavities == 0 && !max_parts_reached && !time_limit_reached;
}

namespace {

// A candidate plane split and scored.
struct Trial
{
	SplitOutcome so;
	// Its parts' measures (the paper's measure itself, the one the recursion uses): the picked
	// plane's become its children's, not measured again.
	std::shared_ptr<const Measured> measures[2];
	bool         ok = false;
	bool         crosses = false;   // keep_cavities: the plane cuts through a kept cavity
	double       score = 0, sum = 0;
	int          sliver = -1;       // the side a rejected plane shaved off
	double       smaller = 0;       // the smaller side's share of the volume
};

// One node's cut: its target (the most concave notch, or a cavity), the candidate planes, their trials.
struct Cut
{
	int                id   = -1;
	int                hole = -1;   // the cavity cut, or -1 for the notch
	CutPlaneSelection  sel  = CutPlaneSelection::Best;
	Vec3               notch = Vec3::Zero();
	std::vector<Plane> planes;
	std::vector<Trial> trials;
	bool               first_fit  = false;   // try planes in order, keep the first that splits
	bool               by_section = false;   // score by the cut's cross-section (MinSection)
	bool               stalled = false;      // the node's own cut made no progress: this one must
	int                pick = -1;
};

// Approx_CD for a solid, as named stages; the recursion's queue and limits are shared with 2D.
class Driver : public Driving<Driver, Decomposition, DecomposeOptions>
{
public:
	explicit Driver(const DecomposeOptions& opt) : Driving(opt, opt.hole_handling == HoleHandling::KeepCavities, kMaxDepth) {}

	Decomposition run(const Solid& solid)
	{
		const std::vector<int> roots = root_nodes(solid);
		for (int id : roots) measure_node(id);
		return finish(roots, &Decomposition::kept_cavities);
	}

	// One node: its target, candidate planes, their trials, the pick; the parts added.
	int cut(int id)
	{
		Cut c;
		c.id = id;
		choose_target(c);
		candidate_planes_for(c);
		unstall(c);
		try_planes(c);
		pick_plane(c);
		widen(c);
		refine_neck(c);
		if (c.pick < 0 && halved_before(id) && drop_film(c)) return 0;
		if (c.pick < 0 && halve(c)) halved.insert(id);
		if (c.pick < 0 && drop_film(c)) return 0;
		return accept(c);
	}

	void forget(int id) { measured[id].reset(); }

private:
	std::vector<std::shared_ptr<const Measured>> measured;   // kept while a node waits to be cut
	std::unordered_map<int, int>           films;      // per node: films dropped (bounded)
	std::unordered_set<int>                halved;     // nodes cut by halve()

	int add_node(TriMesh mesh, int parent, const std::string& path)
	{
		Node n;
		n.parent = parent;
		n.path   = path;
		n.mesh   = std::move(mesh);
		D.nodes.push_back(std::move(n));
		measured.emplace_back();
		return (int) D.nodes.size() - 1;
	}

	// `ms`: the node's mesh already measured (as a scored trial's part), else measured here.
	void measure_node(int id, std::shared_ptr<const Measured> ms = nullptr)
	{
		Node& n = D.nodes[id];
		if (!ms) ms = std::make_shared<const Measured>(n.mesh, keep, opt.tau);
		n.concavity           = ms->rep.max_concavity;
		n.hull_distance       = ms->rep.hull_reach;
		n.hull_distance_bound = ms->rep.hull_reach_bound;
		n.volume              = signed_volume(n.mesh);
		n.notch_count         = ms->rep.notches;
		n.cavities            = (int) ms->cavities.size();
		if (ms->rep.max_vertex >= 0) n.notch = ms->surface(n.mesh).V[ms->rep.max_vertex];
		if (rec.needs_cut(n)) measured[id] = std::move(ms);
	}

	// Several solids (disjoint shells): no notch lies between them, so the measure would call the
	// union convex. Split them off first, one per level (A | rest), keeping the tree binary. The
	// nodes left to cut.
	std::vector<int> root_nodes(const Solid& solid)
	{
		std::vector<TriMesh> solids;
		if (solid.shells > 1) solids = connected_solids(solid.mesh);
		if (solids.size() < 2) return {add_node(solid.mesh, -1, "0")};
		std::vector<int> out;
		int              node = add_node(solid.mesh, -1, "0");
		for (size_t k = 0; k + 1 < solids.size(); ++k) {
			Node& n  = D.nodes[node];
			n.volume = signed_volume(n.mesh);
			n.solids = true;
			const std::string path = n.path;
			TriMesh           rest;
			for (size_t j = k + 1; j < solids.size(); ++j) append(rest, solids[j]);
			const int a = add_node(std::move(solids[k]), node, path + '0');
			const int b = add_node(k + 2 < solids.size() ? std::move(rest) : std::move(solids[k + 1]), node, path + '1');
			D.nodes[node].child[0] = a;
			D.nodes[node].child[1] = b;
			out.push_back(a);
			if (k + 2 == solids.size()) out.push_back(b);
			node = b;
		}
		return out;
	}

	// A cavity is cut when holes go first, when the most concave notch lies on one, or when only
	// cavities are left; the deepest cavity (or the notch's) is the one cut.
	void choose_target(Cut& c) const
	{
		const TriMesh&  mesh = D.nodes[c.id].mesh;
		const Measured& ms   = *measured[c.id];
		if (keep || ms.cavities.empty()) return;
		int    deepest         = -1;
		bool   notch_on_cavity = false;
		double depth           = -1;
		for (int k = 0; k < (int) ms.cavities.size(); ++k)
			for (int f : ms.cavities[k])
				for (int v : mesh.F[f]) {
					notch_on_cavity |= v == ms.rep.max_vertex;
					if (ms.rep.vertex_concavity[v] > depth) depth = ms.rep.vertex_concavity[v], deepest = k;
				}
		if (opt.hole_order == HoleOrder::First || notch_on_cavity || D.nodes[c.id].concavity <= opt.tau) c.hole = deepest;
	}

	// The notch's planes as `best` tries them: the bisector first, then those around its retraction.
	std::vector<Plane> best_planes(int id) const
	{
		const Measured& ms = *measured[id];
		return candidate_planes(ms.surface(D.nodes[id].mesh), ms.topo, ms.hull, ms.rep, CutPlaneSelection::Best, opt.candidate_planes);
	}

	void candidate_planes_for(Cut& c) const
	{
		const TriMesh&  mesh = D.nodes[c.id].mesh;
		const Measured& ms   = *measured[c.id];
		c.sel = opt.cut_plane_selection;
		if (c.hole < 0) {
			c.notch = ms.surface(mesh).V[ms.rep.max_vertex];
			// A notch on the hull itself has no way out to turn a neck's planes around: the paper's
			// bisector it is.
			if (c.sel == CutPlaneSelection::MinSection && !retraction(ms.hull, c.notch)) c.sel = CutPlaneSelection::Bisector;
			c.planes = candidate_planes(ms.surface(mesh), ms.topo, ms.hull, ms.rep, c.sel, opt.candidate_planes, &c.sel);
			if (c.sel == CutPlaneSelection::Bisector && c.planes.size() == 1) {
				// Fall back to the other candidates only if the bisector cannot split.
				const auto more = best_planes(c.id);
				c.planes.insert(c.planes.end(), more.begin() + std::min<size_t>(1, more.size()), more.end());
			}
		}
		else c.planes = cavity_planes(mesh, ms.cavities[c.hole], ms.hull, opt.hole_handling, opt.candidate_planes, c.notch);
		// Try planes in order and keep the first that splits (the paper's planes), or score them all.
		c.first_fit  = c.hole >= 0 ? opt.hole_handling != HoleHandling::BestPlane : c.sel == CutPlaneSelection::Bisector;
		c.by_section = c.hole < 0 && c.sel == CutPlaneSelection::MinSection;
		c.trials.assign(c.planes.size(), Trial());
	}

	// Whether a plane cuts through a cavity (its faces on both sides).
	static bool crosses(const TriMesh& mesh, const std::vector<int>& cavity, const Plane& pl)
	{
		bool neg = false, pos = false;
		for (int f : cavity)
			for (int v : mesh.F[f]) (pl.eval(mesh.V[v]) > 0 ? pos : neg) = true;
		return neg && pos;
	}

	// A plane that takes a chip (volume va or vb, concavity a or b) itself over tau and leaves the rest
	// as concave as the node resolves nothing: two nodes to cut for one, and picked, it would be
	// picked again on the rest, chip after chip.
	bool chips(int id, double va, double vb, double a, double b) const
	{
		const bool   first = va < vb;
		const double chip = first ? a : b, rest = first ? b : a;
		return std::min(va, vb) < 1e-3 * D.nodes[id].volume && chip > opt.tau && rest >= 0.99 * D.nodes[id].concavity;
	}

	// The trial's two parts measured (false: one of them is beyond `beat`, the other left unmeasured).
	// `both_cores` measures the two at once; otherwise the larger part goes first, as the deep notch
	// is more often there.
	bool measure_parts(Trial& t, double va, double vb, double beat, bool both_cores) const
	{
		const auto measure = [&](int s) { t.measures[s] = std::make_shared<const Measured>(t.so.parts[s], keep, opt.tau); };
		if (both_cores) {
			parallel_for(2, [&](size_t s) { measure((int) s); });
			return true;
		}
		const int larger = va < vb ? 1 : 0;
		measure(larger);
		if (!(t.measures[larger]->rep.max_concavity < beat)) return false;
		measure(1 - larger);
		return true;
	}

	// Split the node by candidate i and, with `score`, measure the parts. Trials are independent
	// (each writes its own slot), so they run on all cores. A plane that cannot be picked unless it
	// scores below `beat` stops, not ok, as soon as one part reaches it.
	void trial(Cut& c, size_t i, bool score, double beat = INFINITY, bool both_cores = false) const
	{
		const TriMesh&  mesh = D.nodes[c.id].mesh;
		const Measured& ms   = *measured[c.id];
		const double    v0   = D.nodes[c.id].volume;
		Trial&          t    = c.trials[i];
		t                    = Trial();
		if (!separate(mesh, c.planes[i], c.notch, t.so)) return;
		// A plane that grazes the part shaves off a sliver and resolves nothing.
		const double va = signed_volume(t.so.parts[0]), vb = signed_volume(t.so.parts[1]);
		t.smaller       = std::min(va, vb) / v0;
		if (va < 1e-5 * v0 || vb < 1e-5 * v0) {
			t.sliver = va < vb ? 0 : 1;
			return;
		}
		if (keep)
			for (const auto& cav : ms.cavities) t.crosses |= crosses(mesh, cav, c.planes[i]);
		if (!score) {
			t.ok = true;
			return;
		}
		if (c.by_section) {
			t.score = t.so.cap_area;
			t.ok    = true;
			return;
		}
		try {
			if (!measure_parts(t, va, vb, beat, both_cores)) return;
			const double a = t.measures[0]->rep.max_concavity, b = t.measures[1]->rep.max_concavity;
			if (chips(c.id, va, vb, a, b)) {
				t.sliver = va < vb ? 0 : 1;
				return;
			}
			t.score = std::max(a, b);
			t.sum   = a + b;
			t.ok    = true;
		}
		catch (const Error&) {   // a part with no volume
		}
	}

	// A cut that takes a small piece off and leaves the same notch as deep (a notch on a thin shell,
	// where the bisector runs along the surface) resolves nothing, and the rest would be cut the same
	// way, piece after piece, down to the depth bound. A node made by such a cut must progress: its
	// candidates, the principal planes through its centroid among them, are all scored, and only
	// those that take a real piece off or leave it clearly less concave may be picked.
	bool stalled(int id) const
	{
		const Node& n = D.nodes[id];
		if (n.parent < 0 || D.nodes[n.parent].solids) return false;
		const Node& p = D.nodes[n.parent];
		return n.volume >= 0.99 * p.volume && n.concavity >= 0.99 * p.concavity && (n.notch - p.notch).norm() <= opt.tau;
	}

	bool progresses(const Cut& c, const Trial& t) const
	{
		return t.smaller >= 0.01 || t.score < 0.99 * D.nodes[c.id].concavity;
	}

	void unstall(Cut& c) const
	{
		if (c.hole >= 0 || !stalled(c.id)) return;
		const TriMesh&  mesh = D.nodes[c.id].mesh;
		const Measured& ms   = *measured[c.id];
		c.stalled            = true;
		c.first_fit = c.by_section = false;
		if (c.sel != CutPlaneSelection::Best) {
			const auto more = best_planes(c.id);
			c.planes.insert(c.planes.end(), more.begin(), more.end());
		}
		const Vec3 centre = surface_moments(mesh, Vec3::Zero()).centroid;
		for (int k = 0; k < 3; ++k) c.planes.push_back(through(centre, ms.rep.frame.axes.row(k).transpose()));
		c.trials.assign(c.planes.size(), Trial());
	}

	// A notch charged with its bridge's reach (no vertex shows that depth) has a dihedral angle that
	// need not point across the reach: its plane stands unless it only shaves a tau-convex sliver
	// off and leaves the rest about as concave.
	void try_planes(Cut& c) const
	{
		const bool reach = c.hole < 0 && measured[c.id]->rep.reach_cut;
		if (c.first_fit) {
			// The paper's plane first; the others only if it cannot split.
			int fit = -1;
			for (size_t i = 0; i < c.planes.size() && fit < 0; ++i) {
				trial(c, i, reach);
				if (c.trials[i].ok && !c.trials[i].crosses) fit = (int) i;
			}
			const auto shaves = [&](const Trial& t) {
				return t.sum - t.score <= opt.tau && t.score >= 0.9 * D.nodes[c.id].concavity;
			};
			if (reach && (fit < 0 || shaves(c.trials[fit]))) c.first_fit = false;
		}
		if (c.first_fit) return;
		if (!bisector_stands(c)) {
			parallel_for(c.planes.size(), [&](size_t i) { trial(c, i, true); });
			return;
		}
		// The bisector first: the others need only be scored far enough to see whether they beat it.
		trial(c, 0, true, INFINITY, true);
		const Trial& t0   = c.trials[0];
		const double beat = t0.ok && !t0.crosses ? kClearlyLess * t0.score : INFINITY;
		parallel_for(c.planes.size() - 1, [&](size_t i) { trial(c, i + 1, true, beat); });
	}

	// Whether pick_plane keeps candidate 0, the bisector, unless another scores clearly less.
	static bool bisector_stands(const Cut& c) { return c.hole < 0 && !c.by_section && !c.stalled && c.planes.size() > 1; }

	// The paper's bisector plane (candidate 0) stands unless another leaves clearly (10%) less
	// concavity: greedy scores alone would rather shave small arms off one by one. Among the
	// others, scores within a hair (planes are nudged ~1e-7 of the size off vertices) are ties,
	// settled by the total concavity.
	void pick_plane(Cut& c) const
	{
		const double hair = 1e-6 * extent(D.nodes[c.id].mesh.V);
		const auto&  T    = c.trials;
		int          pick = -1;
		for (const bool allow_crossing : {false, true}) {   // planes that spare kept cavities first
			for (int i = 0; i < (int) T.size(); ++i) {
				const Trial& t = T[i];
				if (!t.ok || (t.crosses && !allow_crossing) || (c.stalled && !progresses(c, t))) continue;
				if (pick < 0 || t.score < T[pick].score - hair || (t.score <= T[pick].score + hair && t.sum < T[pick].sum - hair))
					pick = i;
			}
			if (pick >= 0) break;
		}
		// For a notch (not a cavity, whose planes are all scored alike): see above.
		if (c.hole < 0 && !c.by_section && pick > 0 && T[0].ok && !T[0].crosses && !(c.stalled && !progresses(c, T[0])) &&
		    !(T[pick].score < kClearlyLess * T[0].score))
			pick = 0;
		c.pick = pick;
	}

	// At a sharp edge no plane of the edge splits (each shaves a sliver off): the notch's other
	// planes are scored, as the bisector falls back to them, before the part is halved.
	void widen(Cut& c) const
	{
		if (c.pick >= 0 || c.hole >= 0 || c.stalled || c.sel != CutPlaneSelection::BisectorOrFace) return;
		const auto   more = best_planes(c.id);
		const size_t from = c.planes.size();
		c.planes.insert(c.planes.end(), more.begin() + std::min<size_t>(1, more.size()), more.end());
		c.trials.resize(c.planes.size());
		parallel_for(c.planes.size() - from, [&](size_t i) { trial(c, from + i, true); });
		pick_plane(c);
	}

	// The fan samples the section's area every pi/K: the parabola through the smallest and its
	// neighbours puts the neck between samples, so the plane turns smoothly as the shape does.
	void refine_neck(Cut& c) const
	{
		if (!c.by_section || c.pick < 0 || measured[c.id]->rep.max_bridge < 0) return;
		const int    K = (int) c.planes.size();
		const Trial &l = c.trials[(c.pick + K - 1) % K], &r = c.trials[(c.pick + 1) % K];
		const double curv = l.score - 2 * c.trials[c.pick].score + r.score;
		if (K < 3 || !l.ok || !r.ok || !(curv > 0)) return;
		const double phi  = 0.5 * (l.score - r.score) / curv * M_PI / K;
		const Vec3   axis = c.planes[0].n.cross(c.planes[1].n).normalized(), n = c.planes[c.pick].n;   // the fan's
		c.planes.push_back(through(c.notch, std::cos(phi) * n + std::sin(phi) * axis.cross(n)));
		c.trials.emplace_back();
		trial(c, c.planes.size() - 1, true);
		if (c.trials.back().ok && !c.trials.back().crosses && c.trials.back().score < c.trials[c.pick].score)
			c.pick = (int) c.planes.size() - 1;
	}

	// No candidate splits (the notch sits where every plane through it shaves a sliver): halve the
	// part across its principal axes instead, so that it still shrinks towards tau. A curved strip
	// crossed in its middle falls in three pieces: then cut nearer an end along the same axes. True
	// if it did.
	bool halve(Cut& c) const
	{
		const TriMesh& mesh   = D.nodes[c.id].mesh;
		const Vec3     centre = surface_moments(mesh, Vec3::Zero()).centroid;
		for (const double frac : {0.5, 0.3, 0.7, 0.15, 0.85})
			for (int k = 0; k < 3 && c.pick < 0; ++k) {
				const Vec3 axis = measured[c.id]->rep.frame.axes.row(k).transpose();
				double     lo = INFINITY, hi = -INFINITY;
				for (const Vec3& v : mesh.V) lo = std::min(lo, axis.dot(v - centre)), hi = std::max(hi, axis.dot(v - centre));
				const double at = frac == 0.5 ? 0.0 : lo + frac * (hi - lo);
				c.planes.push_back(through(centre + at * axis, axis));
				c.trials.emplace_back();
				trial(c, c.planes.size() - 1, false);
				if (c.trials.back().ok) c.pick = (int) c.planes.size() - 1;
			}
		return c.pick >= 0;
	}

	// A half of a halved part that no plane splits either: a film is the likelier cause, which
	// halving would keep in one half, to be halved again, so it is dropped first.
	bool halved_before(int id) const { return D.nodes[id].parent >= 0 && halved.count(D.nodes[id].parent) > 0; }

	// Still none: the part may carry a film, two sheets of its surface a rounding error apart (a cut
	// plane a hair off a flat face leaves one). It holds no volume, yet its hull may reach far: drop
	// the widest film a plane shaves off, and measure the rest again. True if one was dropped.
	bool drop_film(Cut& c)
	{
		if (films[c.id] >= kMaxFilms) return false;
		int          drop   = -1;
		double       widest = 0;
		const double size   = extent(D.nodes[c.id].mesh.V);
		for (int i = 0; i < (int) c.trials.size(); ++i) {
			if (c.trials[i].sliver < 0) continue;
			const TriMesh& f = c.trials[i].so.parts[c.trials[i].sliver];
			const double   a = surface_area(f);
			if (std::abs(signed_volume(f)) <= 0.5e-6 * size * a && a > widest) widest = a, drop = i;
		}
		if (drop < 0) return false;
		Trial& t = c.trials[drop];
		++films[c.id];
		++D.films_dropped;
		D.film_volume += std::abs(signed_volume(t.so.parts[t.sliver]));
		D.nodes[c.id].mesh = std::move(t.so.parts[1 - t.sliver]);
		measured[c.id].reset();
		measure_node(c.id);
		rec.push(c.id);
		return true;
	}

	// The picked plane makes the node's two children (measured on two cores, then queued); no plane
	// leaves the node a leaf, reported uncut.
	int accept(Cut& c)
	{
		const int id = c.id;
		measured[id].reset();
		if (c.pick < 0) {
			D.nodes[id].uncut = true;
			return 0;
		}
		SplitOutcome best     = std::move(c.trials[c.pick].so);
		D.nodes[id].has_plane = true;
		D.nodes[id].plane     = best.plane;
		D.nodes[id].hole_cut  = c.hole >= 0;
		D.hole_cuts += c.hole >= 0;
		const std::string path = D.nodes[id].path;
		for (int s = 0; s < 2; ++s) {
			const int child      = add_node(std::move(best.parts[s]), id, path + char('0' + s));
			D.nodes[id].child[s] = child;   // after add_node: it may move D.nodes
		}
		parallel_for(2, [&](size_t s) { measure_node(D.nodes[id].child[s], c.trials[c.pick].measures[s]); });
		for (int s = 0; s < 2; ++s) rec.push(D.nodes[id].child[s]);
		return 1;
	}

	static constexpr double kClearlyLess = 0.9;   // another plane's score must be below this times the bisector's
	static constexpr size_t kMaxDepth = 96;   // tree depth (path length) past which a node stays uncut
	static constexpr int    kMaxFilms = 8;    // films dropped per node, so a node cannot loop
};

} // namespace

Decomposition decompose(const Solid& solid, const DecomposeOptions& opt)
{
	if (!(opt.tau > 0) || !std::isfinite(opt.tau))
		throw Error(Error::InvalidOption, "tau must be a positive, finite length.");
	if (opt.max_parts < 0) throw Error(Error::InvalidOption, "max_parts must be 0 (unbounded) or positive.");
	const auto start = std::chrono::steady_clock::now();

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
	Decomposition D = Driver(o).run(unit);
	if (o.merge_parts) {
		// The time limit bounds the cuts and the merge together; the merge gets what the cuts left.
		const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
		const double left  = o.time_limit_seconds > 0 ? std::max(o.time_limit_seconds - spent, 1e-9) : 0;
		merge_parts(D, o.tau, o.progress, left);
	}
	D.tau = opt.tau;
	for (Node& n : D.nodes) {
		for (Vec3& p : n.mesh.V) p = p * s + c;
		n.concavity *= s;
		n.hull_distance *= s;
		n.hull_distance_bound *= s;
		n.volume *= s * s * s;
		n.notch = n.notch * s + c;
		n.plane.d = n.plane.d * s + n.plane.n.dot(c);
	}
	return D;
}

} // namespace acd
