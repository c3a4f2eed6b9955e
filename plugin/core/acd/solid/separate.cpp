#include "acd/solid/separate.h"
#include "acd/mesh/polygon2.h"
#include "acd/mesh/measures.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace acd {

namespace {

using P2 = Vec2;

struct Loop
{
	std::vector<int> pts;   // crossing-point ids in order
	double           area = 0;
	int              depth = 0, parent = -1;
};

double seg_dist(const P2& p, const P2& a, const P2& b)
{
	P2     ab = b - a;
	double t  = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
	return (a + t * ab - p).norm();
}

// Triangulate one region (outer loop + its direct holes); triangles are CCW in the plane's (u, w)
// frame and index crossing points. False if the loops touch or cross numerically.
bool triangulate_region(const std::vector<std::vector<P2>>& loops2d, const std::vector<Loop>& loops,
                        const std::vector<int>& region, std::vector<Tri>& tris)
{
	Polygon2         poly;
	std::vector<int> id;   // triangulation vertex -> crossing point, in the same loop order
	for (int li : region) {
		(li == region[0] ? poly.outer : poly.holes.emplace_back()) = loops2d[li];
		id.insert(id.end(), loops[li].pts.begin(), loops[li].pts.end());
	}
	std::vector<Vec2> V;
	std::vector<Tri>  F;
	if (!triangulate(poly, V, F)) return false;
	for (const Tri& t : F) tris.push_back({id[t[0]], id[t[1]], id[t[2]]});
	return true;
}

long long edge_id(int a, int b) { return (static_cast<long long>(std::min(a, b)) << 32) | std::max(a, b); }

// Separate by one plane, in stages: crossing points, their loops, the loops' nesting into regions of
// the cross-section, then regions capped nearest to the notch first until the part falls in two.
struct Section
{
	const TriMesh& m;
	const Plane&   plane;
	const int      nv, nf;
	std::vector<double> s;   // signed distance of each vertex to the plane

	std::unordered_map<long long, int> cross_id;      // edge -> crossing point
	std::vector<Vec3>                  cross_pos;
	std::vector<std::array<int, 2>>    cross_faces;   // the two faces holding the crossing edge
	std::vector<std::array<int, 2>>    face_cross;    // per face: its (first two) crossing points
	std::vector<int>                   loop_of;       // per crossing point
	std::vector<Loop>                  loops;
	std::vector<std::vector<P2>>       l2;            // loops in the plane's frame (u, w)
	Vec3                               u, w;
	std::vector<std::vector<int>>      regions;       // an even-depth loop with its direct holes
	std::vector<int>                   region_of;     // per loop

	Section(const TriMesh& m, const Plane& plane)
	    : m(m), plane(plane), nv((int) m.V.size()), nf((int) m.F.size()), s(nv),
	      face_cross(nf, {-1, -1}), u(plane.n.unitOrthogonal()), w(plane.n.cross(u))
	{
		for (int v = 0; v < nv; ++v) s[v] = plane.eval(m.V[v]);
	}

	// Crossing points, one per edge with ends on opposite sides. False if there is none.
	bool crossings()
	{
		for (int f = 0; f < nf; ++f) {
			const Tri& t = m.F[f];
			int        n = 0;
			for (int k = 0; k < 3; ++k) {
				int a = t[k], b = t[(k + 1) % 3];
				if ((s[a] > 0) == (s[b] > 0)) continue;
				auto [it, fresh] = cross_id.emplace(edge_id(a, b), (int) cross_pos.size());
				if (fresh) {
					// Interpolate from the lower index so both faces get the bit-identical point.
					int    lo = std::min(a, b), hi = std::max(a, b);
					double tt = s[lo] / (s[lo] - s[hi]);
					cross_pos.push_back(m.V[lo] + tt * (m.V[hi] - m.V[lo]));
					cross_faces.push_back({f, -1});
				}
				else cross_faces[it->second][1] = f;
				if (n < 2) face_cross[f][n] = it->second;
				++n;
			}
		}
		return !cross_pos.empty();
	}

	// Chain crossing points into closed loops through the faces. False if a chain does not close.
	bool chain_loops()
	{
		loop_of.assign(cross_pos.size(), -1);
		for (int c0 = 0; c0 < (int) cross_pos.size(); ++c0) {
			if (loop_of[c0] >= 0) continue;
			Loop L;
			int  c = c0, f = cross_faces[c0][0];
			while (loop_of[c] < 0) {
				loop_of[c] = (int) loops.size();
				L.pts.push_back(c);
				int nc = face_cross[f][0] == c ? face_cross[f][1] : face_cross[f][0];
				if (nc < 0) return false;
				f = cross_faces[nc][0] == f ? cross_faces[nc][1] : cross_faces[nc][0];
				c = nc;
				if (f < 0) return false;
			}
			if (c != c0 || L.pts.size() < 3) return false;
			loops.push_back(std::move(L));
		}
		return true;
	}

	// Loops in 2D, their areas, depths and smallest enclosing loop; regions. False if a hole has no
	// region around it.
	bool nest_regions()
	{
		l2.resize(loops.size());
		for (size_t i = 0; i < loops.size(); ++i) {
			for (int c : loops[i].pts) l2[i].emplace_back(cross_pos[c].dot(u), cross_pos[c].dot(w));
			double a = 0;
			for (size_t j = 0, k = l2[i].size() - 1; j < l2[i].size(); k = j++)
				a += l2[i][k].x() * l2[i][j].y() - l2[i][j].x() * l2[i][k].y();
			loops[i].area = std::abs(a) / 2;
		}
		for (size_t i = 0; i < loops.size(); ++i)
			for (size_t j = 0; j < loops.size(); ++j)
				if (i != j && inside(l2[j], l2[i][0])) {
					++loops[i].depth;
					if (loops[i].parent < 0 || loops[j].area < loops[loops[i].parent].area) loops[i].parent = (int) j;
				}
		region_of.assign(loops.size(), -1);
		for (size_t i = 0; i < loops.size(); ++i)
			if (loops[i].depth % 2 == 0) {
				region_of[i] = (int) regions.size();
				regions.push_back({(int) i});
			}
		for (size_t i = 0; i < loops.size(); ++i)
			if (loops[i].depth % 2 == 1) {
				if (loops[i].parent < 0 || region_of[loops[i].parent] < 0) return false;
				region_of[i] = region_of[loops[i].parent];
				regions[region_of[i]].push_back((int) i);
			}
		return true;
	}

	// Regions ordered by their distance to the notch; the first holds it.
	std::vector<int> regions_by_distance(const Vec3& notch) const
	{
		const P2            r2(notch.dot(u), notch.dot(w));
		std::vector<double> rdist(regions.size(), std::numeric_limits<double>::infinity());
		for (size_t i = 0; i < loops.size(); ++i)
			for (size_t j = 0, k = l2[i].size() - 1; j < l2[i].size(); k = j++)
				rdist[region_of[i]] = std::min(rdist[region_of[i]], seg_dist(r2, l2[i][k], l2[i][j]));
		std::vector<int> order(regions.size());
		std::iota(order.begin(), order.end(), 0);
		std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return rdist[a] < rdist[b]; });
		return order;
	}

	// The mesh cut along the loops marked in `cut_loop` and closed by `caps` (CCW in (u, w)): original
	// vertices, then per crossing point a negative-side and a positive-side copy.
	TriMesh assemble(const std::vector<char>& cut_loop, const std::vector<Tri>& caps) const
	{
		TriMesh all;
		all.V = m.V;
		for (const Vec3& p : cross_pos) {
			all.V.push_back(p);
			all.V.push_back(p);
		}
		auto neg = [&](int c) { return nv + 2 * c; };
		auto pos = [&](int c) { return nv + 2 * c + 1; };
		for (int f = 0; f < nf; ++f) {
			const Tri& t = m.F[f];
			int        c = face_cross[f][0];
			if (c < 0 || !cut_loop[loop_of[c]]) {
				all.F.push_back(t);
				continue;
			}
			// the lone vertex: the one whose side differs from the other two
			int k = 0;
			for (; k < 3; ++k)
				if ((s[t[k]] > 0) != (s[t[(k + 1) % 3]] > 0) && (s[t[k]] > 0) != (s[t[(k + 2) % 3]] > 0)) break;
			const int  a = t[k], b = t[(k + 1) % 3], d = t[(k + 2) % 3];
			const int  cab = cross_id.at(edge_id(a, b)), cad = cross_id.at(edge_id(a, d));
			const bool a_pos = s[a] > 0;
			auto       lone  = [&](int c2) { return a_pos ? pos(c2) : neg(c2); };
			auto       other = [&](int c2) { return a_pos ? neg(c2) : pos(c2); };
			all.F.push_back({a, lone(cab), lone(cad)});
			all.F.push_back({other(cab), b, d});
			all.F.push_back({other(cab), d, other(cad)});
		}
		for (const Tri& t : caps) {
			all.F.push_back({neg(t[0]), neg(t[1]), neg(t[2])});
			all.F.push_back({pos(t[0]), pos(t[2]), pos(t[1])});
		}
		return all;
	}

	// Two solids the vertex sums put on one side: a piece the cut region took off whole lies on one
	// side only, while the rest, still joined through the regions left uncut, reaches across the plane
	// and may weigh on the same side. The piece keeps its side and the rest takes the other. False
	// when neither or both lie on one side.
	bool one_sided(const std::vector<TriMesh>& solids, std::array<int, 2>& side) const
	{
		double scale = 0;
		for (double x : s) scale = std::max(scale, std::abs(x));
		const double tol = 1e-9 * scale;   // cap vertices lie on the plane up to rounding
		int          whole = -1, count = 0;
		for (int i = 0; i < 2; ++i) {
			bool neg = true, pos = true;
			for (const Vec3& p : solids[i].V) {
				const double e = plane.eval(p);
				neg &= e <= tol, pos &= e >= -tol;
			}
			if (neg != pos) whole = i, side[i] = pos ? 1 : 0, ++count;
		}
		if (count != 1) return false;
		side[1 - whole] = 1 - side[whole];
		return true;
	}

	// Two solids, one on each side (each cavity stays with the outer shell around it): 1 and the parts
	// in `out`; 0 if still one solid (a handle: cut the next region too); -1 if it cannot split.
	int split(const TriMesh& all, const std::vector<Tri>& caps, SplitOutcome& out) const
	{
		std::vector<TriMesh> solids;
		try {
			solids = connected_solids(all);
		}
		catch (const Error&) {
			return -1;
		}
		if (solids.size() < 2) return 0;
		if (solids.size() > 2) return -1;
		std::array<int, 2> side;
		for (int i = 0; i < 2; ++i) {
			double sum = 0;
			for (const Vec3& p : solids[i].V) sum += plane.eval(p);
			side[i] = sum > 0 ? 1 : 0;
		}
		if (side[0] == side[1] && !one_sided(solids, side)) return -1;
		for (int i = 0; i < 2; ++i) out.parts[side[i]] = std::move(solids[i]);
		out.plane    = plane;
		out.cap_area = 0;
		for (const Tri& t : caps)
			out.cap_area += 0.5 * (cross_pos[t[1]] - cross_pos[t[0]]).cross(cross_pos[t[2]] - cross_pos[t[0]]).norm();
		return 1;
	}
};

bool separate_at(const TriMesh& m, const Plane& plane, const Vec3& notch, SplitOutcome& out)
{
	Section sec(m, plane);
	if (!sec.crossings() || !sec.chain_loops() || !sec.nest_regions()) return false;
	const std::vector<int> order = sec.regions_by_distance(notch);
	std::vector<char>      cut_loop(sec.loops.size(), 0);
	std::vector<Tri>       caps;   // CCW in (u, w): outward normal +n, i.e. the negative side's cap
	for (size_t ri = 0; ri < order.size(); ++ri) {
		const std::vector<int>& region = sec.regions[order[ri]];
		if (!triangulate_region(sec.l2, sec.loops, region, caps)) return false;
		for (int li : region) cut_loop[li] = 1;
		out.regions_cut = (int) ri + 1;
		const int split = sec.split(sec.assemble(cut_loop, caps), caps, out);
		if (split != 0) return split > 0;
	}
	return false;
}

} // namespace

std::vector<TriMesh> connected_solids(const TriMesh& all)
{
	int                  ncomp = 0;
	std::vector<int>     comp  = face_components(all, &ncomp);
	std::vector<TriMesh> shells(ncomp);
	std::vector<int>     remap(all.V.size(), -1), remap_comp(all.V.size(), -1);
	for (int f = 0; f < (int) all.F.size(); ++f) {
		TriMesh& sh = shells[comp[f]];
		Tri      t;
		for (int k = 0; k < 3; ++k) {
			const int v = all.F[f][k];
			if (remap_comp[v] != comp[f]) {
				remap_comp[v] = comp[f];
				remap[v]      = (int) sh.V.size();
				sh.V.push_back(all.V[v]);
			}
			t[k] = remap[v];
		}
		sh.F.push_back(t);
	}
	std::vector<double> vol(ncomp);
	std::vector<int>    outer, cavity;
	for (int c = 0; c < ncomp; ++c) {
		vol[c] = signed_volume(shells[c]);
		(vol[c] > 0 ? outer : cavity).push_back(c);
	}
	// Largest first; equal volumes keep their order (a stable, pose-free order would need more).
	std::stable_sort(outer.begin(), outer.end(), [&](int a, int b) { return vol[a] > vol[b]; });
	std::vector<TriMesh> solids;
	for (int c : outer) solids.push_back(shells[c]);
	for (int c : cavity) {
		int host = -1;   // the smallest outer shell around the cavity
		for (int i = (int) outer.size() - 1; i >= 0 && host < 0; --i)
			if (inside(shells[outer[i]], shells[c].V[0])) host = i;
		if (host < 0) throw Error(Error::InvalidInput, "An inward-facing shell lies outside every solid.");
		append(solids[host], shells[c]);
	}
	return solids;
}

bool separate(const TriMesh& m, const Plane& plane, const Vec3& notch, SplitOutcome& out)
{
	// Keep every vertex clearly off the plane (the paper's perturbation of vertices on the plane):
	// slide the plane by tiny offsets until no vertex is within `gap` of it.
	const double diag = extent(m.V);
	const double gap  = 1e-9 * diag;
	for (double off : {0.0, 1e-7, -1e-7, 3.1e-7, -3.1e-7, 1.3e-6, -1.3e-6}) {
		Plane p = plane;
		p.d += off * diag;
		bool clear = true;
		for (const Vec3& v : m.V)
			if (std::abs(p.eval(v)) <= gap) {
				clear = false;
				break;
			}
		if (clear && separate_at(m, p, notch, out)) return true;
	}
	return false;
}

} // namespace acd
