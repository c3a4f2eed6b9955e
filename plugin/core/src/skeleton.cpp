#include "acd/skeleton.h"

#include <algorithm>
#include <cmath>
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

// Parameters where the line c + t a crosses the mesh, sorted.
std::vector<double> crossings(const TriMesh& m, const Vec3& c, const Vec3& a)
{
	std::vector<double> ts;
	for (const Tri& t : m.F) {
		const Vec3 &p = m.V[t[0]], &q = m.V[t[1]], &r = m.V[t[2]];
		const Vec3   e1 = q - p, e2 = r - p, h = a.cross(e2);
		const double det = e1.dot(h);
		if (std::abs(det) < 1e-300) continue;
		const Vec3   s = c - p;
		const double u = s.dot(h) / det;
		if (u < 0 || u > 1) continue;
		const Vec3   qv = s.cross(e1);
		const double v  = a.dot(qv) / det;
		if (v < 0 || u + v > 1) continue;
		ts.push_back(e2.dot(qv) / det);
	}
	std::sort(ts.begin(), ts.end());
	// a crossing through a shared edge or vertex is found once per face: merge near-equal ones
	std::vector<double> out;
	for (double t : ts)
		if (out.empty() || t - out.back() > 1e-12) out.push_back(t);
	return out;
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

	// The chord of the axis through the centroid; whether the piece must be refined.
	bool chord(Piece& p)
	{
		p.c = centroid(p.mesh);
		p.a = pose_frame(p.mesh).axes.row(0).transpose();
		const std::vector<double> ts = crossings(p.mesh, p.c, p.a);
		// inside intervals are consecutive pairs; take the one holding the centroid, else the nearest
		int best = -1;
		double gap = HUGE_VAL;
		for (size_t i = 0; i + 1 < ts.size(); i += 2) {
			const double d = ts[i] > 0 ? ts[i] : ts[i + 1] < 0 ? -ts[i + 1] : 0;
			if (d < gap) gap = d, best = (int) i;
		}
		if (best < 0) {   // no crossing found (degenerate): a point
			p.lo = p.hi = p.mid = 0;
			return false;
		}
		p.lo  = ts[best];
		p.hi  = ts[best + 1];
		p.mid = gap > 0 ? (p.lo + p.hi) / 2 : 0;
		const bool leaves    = ts.size() > 2;   // the axis leaves the piece and comes back
		const bool off       = std::abs((p.lo + p.hi) / 2) > opt.off_centre * (p.hi - p.lo);
		return leaves || off || gap > 0;
	}

	// A cut between the pieces `A` and `B` (plane `pl`): join them through its cross-section's centre.
	void joint(const Plane& pl, const std::vector<int>& A, const std::vector<int>& B)
	{
		auto cap = [&](const std::vector<int>& side, Vec3& centre) {
			double area = 0;
			centre      = Vec3::Zero();
			for (int i : side)
				for (const Tri& t : pieces[i].mesh.F) {
					const Vec3 &p = pieces[i].mesh.V[t[0]], &q = pieces[i].mesh.V[t[1]], &r = pieces[i].mesh.V[t[2]];
					if (std::abs(pl.eval(p)) > eps || std::abs(pl.eval(q)) > eps || std::abs(pl.eval(r)) > eps) continue;
					const double w = 0.5 * (q - p).cross(r - p).norm();
					area += w;
					centre += w * (p + q + r) / 3;
				}
			if (area > 0) centre /= area;
			return area;
		};
		Vec3 q;
		if (!(cap(A, q) > 0)) return;
		const int jq = add_vertex(q, -1);
		for (const std::vector<int>* side : {&A, &B}) {
			// the piece of this side whose cap faces lie nearest to the centre
			int    pick = -1;
			double dmin = HUGE_VAL;
			for (int i : *side) {
				Vec3 ci;
				if (!(cap({i}, ci) > 0)) continue;
				const double d = (ci - q).norm();
				if (d < dmin) dmin = d, pick = i;
			}
			// joined to the piece's centre: both lie in the (nearly convex) piece, so does the edge
			if (pick >= 0) pieces[pick].joints.push_back(jq);
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
		if (chord(p) && level < opt.max_refinement) {
			SplitOutcome so;
			Plane        pl;
			pl.n = p.a;
			pl.d = p.a.dot(p.c + p.mid * p.a);
			if (separate(p.mesh, pl, p.c + p.mid * p.a, so)) {
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

	std::vector<int> build(int id)
	{
		const Node& n = D.nodes[id];
		if (n.leaf()) return refine(n.mesh, 0);
		std::vector<int> a = build(n.child[0]), b = build(n.child[1]);
		if (n.has_plane) joint(n.plane, a, b);
		a.insert(a.end(), b.begin(), b.end());
		return a;
	}
};

} // namespace

int Skeleton::components() const
{
	std::vector<int> parent(V.size());
	std::iota(parent.begin(), parent.end(), 0);
	auto root = [&](int x) {
		while (parent[x] != x) x = parent[x] = parent[parent[x]];
		return x;
	};
	for (const auto& e : E) parent[root(e[0])] = root(e[1]);
	int n = 0;
	for (int v = 0; v < (int) V.size(); ++v) n += root(v) == v;
	return n;
}

Skeleton skeleton(const Decomposition& D, const SkeletonOptions& opt)
{
	Builder b{D, opt, 1e-9 * extent(D.nodes[0].mesh.V), {}, {}};
	b.build(0);
	// Each piece: its axis chord through its centre, and edges from the centre to its joints.
	for (int i = 0; i < (int) b.pieces.size(); ++i) {
		const Piece& p   = b.pieces[i];
		const int    lo  = b.add_vertex(p.c + p.lo * p.a, i);
		const int    mid = b.add_vertex(p.c + p.mid * p.a, i);
		const int    hi  = b.add_vertex(p.c + p.hi * p.a, i);
		b.S.E.push_back({lo, mid});
		b.S.E.push_back({mid, hi});
		for (int j : p.joints) b.S.E.push_back({j, mid});
	}
	b.S.pieces = (int) b.pieces.size();
	return std::move(b.S);
}

} // namespace acd
