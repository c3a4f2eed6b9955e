#include "acd/decompose3/cut_planes.h"
#include "acd/decompose3/concavity.h"
#include "acd/mesh/measures.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace acd {

namespace {

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

} // namespace

const std::vector<CutStrategy>& cut_strategies()
{
	static const std::vector<CutStrategy> table = {
		{CutPlaneSelection::Best, "best",
		 "try several planes through the notch (the bisector, planes around its retraction direction, the plane "
		 "parallel to its bridge) and keep the one leaving the least concave parts"},
		{CutPlaneSelection::Bisector, "bisector",
		 "the paper's plane through the notch edge bisecting its reflex angle (faster)"},
		{CutPlaneSelection::MinSection, "min_section",
		 "of the planes through the notch and its retraction direction, the one cutting the smallest "
		 "cross-section (the neck), which surface noise hardly moves (the skeleton's default)"},
		{CutPlaneSelection::BisectorOrFace, "bisector_or_face",
		 "the bisector, or at a sharp notch edge (a CAD step, slot or flange) one of its two faces extended, or "
		 "the plane of the rim the notch edge lies on (a groove's or step's ring), or the flat a shallow notch "
		 "rises from (a low boss or ramp on a plate), when that leaves clearly less concave parts (near the "
		 "bisector's speed)"},
	};
	return table;
}

namespace {

// What every strategy looks at: the notch, its most reflex edge, and the ways out of its pocket.
struct NotchSite
{
	const TriMesh&         m;
	const Topology&        topo;
	const ConvexHull&      hull;
	const ConcavityReport& rep;
	int                    around;
	bool                   axes = false;
	int                    r;
	Vec3                   p;
	NotchEdge              ne;
	NotchSite(const TriMesh& m, const Topology& topo, const ConvexHull& hull, const ConcavityReport& rep, int around)
	    : m(m), topo(topo), hull(hull), rep(rep), around(around), r(rep.max_vertex),
	      p(r >= 0 ? m.V[r] : Vec3::Zero()), ne(r >= 0 ? notch_edge(m, topo, r, rep.frame) : NotchEdge())
	{
	}
	std::optional<Plane> bisector() const
	{
		return ne.bisects() ? std::optional<Plane>(through(p, ne.dir.cross(ne.bis))) : std::nullopt;
	}
	std::optional<Vec3> rim() const { return ne.excess > 0 ? rim_normal(m, topo, r, ne) : std::nullopt; }
};

// Planes containing the retraction direction (the bridge's normal, or with `nearest` the way to the
// nearest hull point), at evenly spread angles starting from the notch edge's direction, and with
// `parallel` the plane parallel to the bridge. A notch charged with its bridge's reach: which of
// equally far bridges holds the farthest point is the search's rounding, so the fan turns about the
// notch edge instead.
void retraction_fan(const NotchSite& s, std::vector<Plane>& out, bool nearest, bool parallel)
{
	const NotchEdge& ne = s.ne;
	if (s.rep.reach_cut && !nearest && ne.bisects()) {
		const Vec3 n0 = ne.dir.cross(ne.bis).normalized();
		fan(out, s.p, n0, ne.dir.cross(n0), s.around, 1);
	}
	else if (s.rep.max_bridge >= 0) {
		const std::optional<Vec3> out_dir = nearest ? retraction(s.hull, s.p) : std::nullopt;
		const Vec3                nb      = out_dir ? *out_dir : s.hull.facet_plane[s.rep.max_bridge].n;
		Vec3                      u       = ne.dir - nb * nb.dot(ne.dir);
		if (u.norm() < 1e-9) u = nb.unitOrthogonal();
		u.normalize();
		fan(out, s.p, u, nb.cross(u), s.around);
		if (parallel) out.push_back(through(s.p, nb));
	}
}

CutPlan best(const NotchSite& s)
{
	CutPlan plan{{}, CutPolicy::BisectorStands, true, false};
	if (s.r < 0) return plan;
	if (const auto b = s.bisector()) plan.planes.push_back(*b);
	if (s.ne.sharp())
		for (const Vec3& n : s.ne.faces) plan.planes.push_back(through(s.p, n));
	if (const auto rim = s.rim()) plan.planes.push_back(through(s.p, *rim));
	retraction_fan(s, plan.planes, false, true);
	return plan;
}

// The bisector alone; where it cannot split, Best's other planes in order. A notch edge that does not
// bisect: the fan about its bridge's normal and the plane parallel to the bridge.
CutPlan bisector(const NotchSite& s)
{
	CutPlan plan{{}, CutPolicy::FirstFit, false, false};
	if (s.r < 0) return plan;
	if (const auto b = s.bisector()) {
		const std::vector<Plane> more = best(s).planes;
		plan.planes.push_back(*b);
		plan.planes.insert(plan.planes.end(), more.begin() + std::min<size_t>(1, more.size()), more.end());
		return plan;
	}
	retraction_fan(s, plan.planes, false, true);
	if (plan.planes.size() == 1) {
		const std::vector<Plane> more = best(s).planes;
		plan.planes.insert(plan.planes.end(), more.begin() + std::min<size_t>(1, more.size()), more.end());
	}
	return plan;
}

// The fan about the way to the nearest hull point, scored by section; a notch on the hull itself has
// no way out to turn a neck's planes around: the paper's bisector it is.
CutPlan min_section(const NotchSite& s)
{
	if (s.r >= 0 && !retraction(s.hull, s.p)) return bisector(s);
	CutPlan plan{{}, CutPolicy::BySection, false, false};
	if (s.r >= 0) retraction_fan(s, plan.planes, true, false);
	return plan;
}

// The planes through the notch across the part's principal axes, those the pose cannot turn and that
// no plane of the plan already lies along: a step or slab is taken off along the part's own lie, where
// the notch's faces and bisector tilt with the notch (a boss whose wall meets a sloping floor).
void principal_planes(const NotchSite& s, std::vector<Plane>& planes)
{
	const PoseFrame& fr = s.rep.frame;
	for (int k = 0; k < 3; ++k) {
		const Vec3 n   = fr.axes.row(k).transpose();
		bool       dup = !fr.distinct(k);
		for (const Plane& q : planes) dup = dup || std::abs(q.n.dot(n)) > 1 - 1e-9;
		if (!dup) planes.push_back(through(s.p, n));
	}
}

// The notch's two faces extended (a CAD step, slot or flange cut off along its own face: only at a sharp
// reflex edge, 30 degrees or more from flat; on a smooth or wrapped surface the faces' planes are
// near-tangent slices), the rim's plane and the floor's, after the bisector, and with `axes` the
// principal planes; none of these: the bisector.
CutPlan bisector_or_face(const NotchSite& s)
{
	if (s.r < 0) return bisector(s);
	const std::optional<Plane> b     = s.bisector();
	const bool                 sharp = s.ne.sharp();
	const std::optional<Vec3>  rim   = s.rim();
	const std::optional<Vec3>  floor = !sharp && !rim && s.ne.excess > 0 && !s.rep.reach_cut && s.rep.max_bridge >= 0
	                                       ? floor_normal(s.m, s.p, s.ne, s.hull.facet_plane[s.rep.max_bridge].n)
	                                       : std::nullopt;
	if (!b || !(sharp || rim || floor || s.axes)) return bisector(s);
	CutPlan             plan{{*b}, CutPolicy::BisectorStands, false, true};
	std::array<Vec3, 2> faces = s.ne.faces;
	// After the bisector, in the part's frame's order: a tie goes the same way in any pose.
	if (s.rep.frame.before(s.p + faces[1], s.p + faces[0])) std::swap(faces[0], faces[1]);
	if (sharp) plan.planes = {*b, through(s.p, faces[0]), through(s.p, faces[1])};
	if (rim) plan.planes.push_back(through(s.p, *rim));
	if (floor) plan.planes.push_back(through(s.p, *floor));
	if (s.axes) principal_planes(s, plan.planes);
	return plan;
}

// One function per strategy, by the enum's value.
using Strategy = CutPlan (*)(const NotchSite&);
Strategy strategy(CutPlaneSelection sel)
{
	switch (sel) {
	case CutPlaneSelection::Bisector: return bisector;
	case CutPlaneSelection::Best: return best;
	case CutPlaneSelection::MinSection: return min_section;
	case CutPlaneSelection::BisectorOrFace: return bisector_or_face;
	}
	return bisector;
}

} // namespace

CutPlan plan_notch_cut(const TriMesh& m, const Topology& topo, const ConvexHull& hull, const ConcavityReport& rep,
                       CutPlaneSelection sel, int around, bool axes)
{
	NotchSite s(m, topo, hull, rep, around);
	s.axes = axes;
	return strategy(sel)(s);
}

std::vector<Plane> all_notch_planes(const TriMesh& m, const Topology& topo, const ConvexHull& hull,
                                    const ConcavityReport& rep, int around)
{
	return best(NotchSite(m, topo, hull, rep, around)).planes;
}

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

} // namespace acd
