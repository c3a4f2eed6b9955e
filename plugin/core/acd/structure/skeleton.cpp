#include "acd/structure/skeleton.h"

#include "acd/mesh/disjoint_sets.h"
#include "acd/hull/hull.h"
#include "acd/mesh/measures.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <numeric>

namespace acd {

namespace {

// Volume centroid of a closed mesh (signed tetrahedra from a vertex of it).
Vec3 centroid(const TriMesh& m)
{
	const Vec3 o = m.V[m.F[0][0]];
	Vec3       c = Vec3::Zero();
	double     v = 0;
	for (const Tri& t : m.F) {
		const Vec3   a = m.V[t[0]] - o, b = m.V[t[1]] - o, d = m.V[t[2]] - o;
		const double w = a.dot(b.cross(d));
		v += w;
		c += w * (a + b + d) / 4;
	}
	return std::abs(v) > 0 ? Vec3(o + c / v) : o;
}

// Major principal axis of a closed surface's area about c.
Vec3 principal_axis(const TriMesh& m, const Vec3& c)
{
	Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(surface_moments(m, c).second);   // ascending
	return es.eigenvectors().col(2);
}

struct Piece
{
	TriMesh mesh;
	Vec3    c = Vec3::Zero(), a = Vec3::UnitX();
	double  lo = 0, hi = 0, mid = 0;   // the chord [lo, hi] along a, its point for the piece
	std::vector<int> joints;   // cut-centre vertices joined to this piece's centre
};

struct Builder
{
	const Decomposition&   D;
	const SkeletonOptions& opt;
	double                 eps;   // points this close to a cut plane lie on it
	std::vector<Piece>     pieces;
	Skeleton               S;

	// The principal axis of `mesh`'s convex hull through the hull's centroid (the paper's: the hull
	// ignores surface noise), clipped to the mesh, into p. The piece needs splitting when the chord
	// inside spans less than min_cover of the axis across the hull, or runs off-centre. Gaps shorter
	// than tau / 10 and inside stretches shorter than tau are surface features, not the shape's.
	bool chord(const TriMesh& mesh, Piece& p, bool along)
	{
		const TriMesh hull = ConvexHull(mesh.V).mesh();
		p.c = centroid(hull);
		p.a = principal_axis(hull, p.c);
		const std::vector<double> across = line_crossings(hull, p.c, p.a);
		const std::vector<double> ts     = line_crossings(mesh, p.c, p.a);
		std::vector<std::array<double, 2>> in;   // inside intervals, small gaps closed, slivers dropped
		for (size_t i = 0; i + 1 < ts.size(); i += 2) {
			if (!in.empty() && ts[i] - in.back()[1] < 0.1 * D.tau) in.back()[1] = ts[i + 1];
			else in.push_back({ts[i], ts[i + 1]});
		}
		if (in.size() > 1) {   // unless all are that short (tau can be large): then they are the shape
			std::vector<std::array<double, 2>> long_enough;
			std::copy_if(in.begin(), in.end(), std::back_inserter(long_enough), [&](const auto& r) { return r[1] - r[0] >= D.tau; });
			if (!long_enough.empty()) in.swap(long_enough);
		}
		// the interval holding the centroid, else the nearest
		int    best = -1;
		double gap  = HUGE_VAL;
		for (int i = 0; i < (int) in.size(); ++i) {
			const double d = in[i][0] > 0 ? in[i][0] : in[i][1] < 0 ? -in[i][1] : 0;
			if (d < gap) gap = d, best = i;
		}
		if (best < 0 || across.size() < 2) {   // the axis misses the solid: split there; degenerate: a point
			p.lo = p.hi = p.mid = 0;
			return across.size() >= 2;
		}
		p.lo  = in[best][0];
		p.hi  = in[best][1];
		p.mid = gap > 0 ? (p.lo + p.hi) / 2 : 0;
		const bool leaves = p.hi - p.lo < opt.min_cover * (across.back() - across.front());
		const bool off    = std::abs((p.lo + p.hi) / 2) > opt.off_centre * (p.hi - p.lo);
		if (leaves || off || gap > 0) return true;
		if (!along) return false;
		// Centred along its length too: at stations along the middle of the chord, the solid's extent
		// across the axis (two directions) is centred on the chord. A node bent at a joint (a body with
		// its neck) has a chord that stays inside but runs along one side. (Not asked of leaves: they
		// are tau-convex, and their ends are caps, rarely centred.)
		const Vec3 u = p.a.unitOrthogonal(), v = p.a.cross(u);
		for (int k = 1; k <= 7; ++k) {
			const Vec3 x = p.c + (p.lo + (p.hi - p.lo) * k / 8) * p.a;
			for (const Vec3& d : {u, v}) {
				const std::vector<double> s = line_crossings(mesh, x, d);
				for (size_t i = 0; i + 1 < s.size(); i += 2)
					if (s[i] <= 0 && s[i + 1] >= 0 && std::abs(s[i] + s[i + 1]) / 2 > opt.off_centre * (s[i + 1] - s[i]))
						return true;
			}
		}
		return false;
	}

	struct CapFace
	{
		int    piece;
		Vec3   centroid;
		double area;
		int    corner[3];   // welded corner ids (equal positions, across pieces)
	};

	// Faces of the pieces lying on plane `pl` (the caps of that cut), corners welded by position.
	std::vector<CapFace> caps(const Plane& pl, const std::vector<int>& side, std::map<std::array<double, 3>, int>& weld)
	{
		std::vector<CapFace> out;
		for (int i : side)
			for (const Tri& t : pieces[i].mesh.F) {
				const Vec3 &p = pieces[i].mesh.V[t[0]], &q = pieces[i].mesh.V[t[1]], &r = pieces[i].mesh.V[t[2]];
				if (std::abs(pl.eval(p)) > eps || std::abs(pl.eval(q)) > eps || std::abs(pl.eval(r)) > eps) continue;
				CapFace f{i, (p + q + r) / 3, 0.5 * (q - p).cross(r - p).norm(), {}};
				for (int k = 0; k < 3; ++k) {
					const Vec3& x = pieces[i].mesh.V[t[k]];
					f.corner[k]   = weld.emplace(std::array<double, 3>{x.x(), x.y(), x.z()}, (int) weld.size()).first->second;
				}
				out.push_back(f);
			}
		return out;
	}

	// A cut between the pieces `A` and `B` (plane `pl`): join them through the centre of each
	// connected cross-section (a cut through a ring meets it twice: two joints, so the loop closes).
	void joint(const Plane& pl, const std::vector<int>& A, const std::vector<int>& B)
	{
		std::map<std::array<double, 3>, int> weld;
		const std::vector<CapFace> a = caps(pl, A, weld), b = caps(pl, B, weld);
		if (a.empty()) return;
		// connected components of A's cap faces through shared corners
		DisjointSets sets(weld.size());
		for (const CapFace& f : a) {
			sets.unite(f.corner[2], f.corner[1]);
			sets.unite(f.corner[0], f.corner[1]);
		}
		std::map<int, std::pair<Vec3, double>> section;   // root -> (area-weighted centroid sum, area)
		for (const CapFace& f : a) {
			auto& [c, w] = section.try_emplace(sets.root(f.corner[0]), Vec3::Zero(), 0.0).first->second;
			c += f.area * f.centroid, w += f.area;
		}
		for (const auto& [r, cw] : section) {
			if (!(cw.second > 0)) continue;
			const Vec3 q  = cw.first / cw.second;
			const int  jq = add_vertex(q, -1);
			for (const std::vector<CapFace>* side : {&a, &b}) {
				// the piece of this side holding the cap face nearest to the section's centre
				int    pick = -1;
				double dmin = HUGE_VAL;
				for (const CapFace& f : *side)
					if ((side == &b || sets.root(f.corner[0]) == r) && (f.centroid - q).norm() < dmin)
						dmin = (f.centroid - q).norm(), pick = f.piece;
				if (pick >= 0) pieces[pick].joints.push_back(jq);
			}
		}
	}

	int add_vertex(const Vec3& x, int piece)
	{
		S.V.push_back(x);
		S.piece.push_back(piece);
		return (int) S.V.size() - 1;
	}

	std::vector<int> refine(TriMesh mesh, int level)
	{
		Piece p;
		p.mesh = std::move(mesh);
		if (chord(p.mesh, p, false) && level < opt.max_refinement) {
			// across the axis through the centroid: a bent piece halves at its bend
			SplitOutcome so;
			Plane        pl;
			pl.n = p.a;
			pl.d = p.a.dot(p.c);
			if (separate(p.mesh, pl, p.c, so)) {
				++S.refined;
				std::vector<int> a = refine(std::move(so.parts[0]), level + 1);
				std::vector<int> b = refine(std::move(so.parts[1]), level + 1);
				joint(so.plane, a, b);
				a.insert(a.end(), b.begin(), b.end());
				return a;
			}
		}
		pieces.push_back(std::move(p));
		return {(int) pieces.size() - 1};
	}

	// Top down (the paper's Figure 14): a node whose hull axis is good is one piece, however coarse;
	// otherwise its cut splits it, and a leaf that is still not good is split across its axis.
	std::vector<int> build(int id)
	{
		const Node& n = D.nodes[id];
		if (n.leaf()) return refine(n.mesh, 0);
		Piece p;
		if (!chord(n.mesh, p, true)) {
			p.mesh = n.mesh;   // kept whole: its caps are needed for the joints
			pieces.push_back(std::move(p));
			return {(int) pieces.size() - 1};
		}
		std::vector<int> a = build(n.child[0]), b = build(n.child[1]);
		if (n.has_plane) joint(n.plane, a, b);
		a.insert(a.end(), b.begin(), b.end());
		return a;
	}
};

} // namespace

int Skeleton::components() const
{
	DisjointSets sets(V.size());
	for (const auto& e : E) sets.unite(e[0], e[1]);
	int n = 0;
	for (int v = 0; v < (int) V.size(); ++v) n += sets.root(v) == v;
	return n;
}

Skeleton skeleton(const Decomposition& D, const SkeletonOptions& opt)
{
	Builder b{D, opt, 1e-9 * extent(D.nodes[0].mesh.V), {}, {}};
	b.build(0);
	// Each piece: its axis chord, and an edge from each joint to the chord's nearest point (a coarse
	// piece is not convex: its centre may not see the joint, its axis runs nearer).
	for (int i = 0; i < (int) b.pieces.size(); ++i) {
		const Piece&                     p = b.pieces[i];
		std::vector<std::pair<double, int>> at{{p.lo, -1}, {p.mid, -1}, {p.hi, -1}};   // (t, joint)
		for (int j : p.joints) at.push_back({std::clamp((b.S.V[j] - p.c).dot(p.a), p.lo, p.hi), j});
		std::sort(at.begin(), at.end());
		int prev = -1;
		double tprev = 0;
		for (const auto& [t, j] : at) {
			if (prev < 0 || t > tprev) {
				const int v = b.add_vertex(p.c + t * p.a, i);
				if (prev >= 0) b.S.E.push_back({prev, v});
				prev = v, tprev = t;
			}
			if (j >= 0) b.S.E.push_back({j, prev});
		}
	}
	b.S.pieces = (int) b.pieces.size();
	return std::move(b.S);
}

} // namespace acd
