// Decimation in rounds (decimate.h): every round measures each edge's collapse, then collapses the
// cheapest ones whose ends are untouched so far in the round. A collapse changes the position, quadric
// and faces of its kept vertex only (its neighbours keep their face ids, two of them dead), so every
// other edge's measure and adjacency stay exact for the rest of the round. No heap, no half-edge
// structure: a round is a sort and a sweep, which keeps millions of faces to seconds.
#include "acd/mesh/decimate.h"
#include "acd/mesh/measures.h"
#include "acd/mesh/parallel.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

namespace acd {

namespace {

// Area-weighted sum of squared distances to planes: p'Ap + 2b'p + c, over a total area w.
struct Quadric
{
	Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
	Vec3            b = Vec3::Zero();
	double          c = 0, w = 0;
	void add_plane(const Vec3& n, double d, double area)
	{
		A += area * n * n.transpose();
		b -= area * d * n;
		c += area * d * d;
		w += area;
	}
	Quadric& operator+=(const Quadric& o)
	{
		A += o.A, b += o.b, c += o.c, w += o.w;
		return *this;
	}
	// Mean squared distance of p to the planes.
	double mean(const Vec3& p) const { return w > 0 ? std::max(0.0, p.dot(A * p) + 2 * b.dot(p) + c) / w : 0; }
};

struct Collapse
{
	double cost = 0;
	int    u = -1, v = -1;   // v goes into u
	Vec3   p = Vec3::Zero();
	bool   operator<(const Collapse& o) const { return cost != o.cost ? cost < o.cost : u != o.u ? u < o.u : v < o.v; }
};

class Decimator
{
public:
	Decimator(TriMesh m, double max_error)   // taken whole: decimate() hands it its own copy
	    : V(std::move(m.V)), F(std::move(m.F)), Q(V.size()), bar(max_error * max_error), floor(1e-12 * std::pow(bbox_diagonal(V), 2))
	{
		for (const Tri& t : F) {
			const Vec3   n    = (V[t[1]] - V[t[0]]).cross(V[t[2]] - V[t[0]]);
			const double area = 0.5 * n.norm();
			if (!(area > 0)) continue;
			const Vec3 u = n.normalized();
			for (int v : t) Q[v].add_plane(u, u.dot(V[t[0]]), area);
		}
	}

	// One round: false when nothing could be collapsed. The collapses are taken in order; each block of
	// them is first judged on every core against the mesh as the block starts, and a judgement is kept
	// where no collapse in the block has touched the faces it read (else judged again in turn), so the
	// round takes exactly the collapses a plain sweep would.
	bool round(size_t target)
	{
		index_faces();
		cheapest();
		locked.assign(V.size(), 0);
		touched.assign(V.size(), -1);
		size_t faces = F.size(), done = 0;
		for (size_t b = 0; b < order.size() && faces > target; b += kBlock) {
			const size_t e     = std::min(order.size(), b + kBlock);
			const int    block = (int) (b / kBlock);
			guess.resize(e - b);
			parallel_for_chunked(e - b, 1024, [&](size_t k) {
				const Collapse& c = order[b + k];
				guess[k]          = locked[c.u] || locked[c.v] ? Guess{} : judge(c);
			});
			for (size_t i = b; i < e && faces > target; ++i) {
				const Collapse& c = order[i];
				if (locked[c.u] || locked[c.v]) continue;
				const Guess& g     = guess[i - b];
				const bool   fresh = touched[c.u] != block && touched[c.v] != block &&
				                   (g.opposite[0] < 0 || (touched[g.opposite[0]] != block && touched[g.opposite[1]] != block));
				if (!(fresh ? g.ok : judge(c).ok)) continue;
				touch(c, block);
				collapse(c);
				faces -= 2;
				++done;
			}
		}
		compact_faces();
		return done > 0;
	}

	size_t  faces() const { return F.size(); }
	TriMesh mesh() const
	{
		TriMesh          out;
		std::vector<int> id(V.size(), -1);
		for (const Tri& t : F)
			for (int v : t) id[v] = 0;
		for (size_t v = 0; v < V.size(); ++v)
			if (id[v] == 0) id[v] = (int) out.V.size(), out.V.push_back(V[v]);
		for (const Tri& t : F) out.F.push_back({id[t[0]], id[t[1]], id[t[2]]});
		return out;
	}

private:
	std::vector<Vec3>    V;
	std::vector<Tri>     F;
	std::vector<Quadric> Q;
	const double         bar, floor;
	std::vector<int>     start, incident;   // faces around each vertex (at the round's start)
	std::vector<char>    dead, locked;
	std::vector<int>     touched;   // the last block of the round whose collapses changed a vertex's faces
	struct Scratch   // judge()'s
	{
		std::vector<int> ring[2], opposite, common;
	};
	struct Guess
	{
		bool ok = false;
		int  opposite[2] = {-1, -1};   // the link's two opposite vertices, when their degrees were read
	};
	std::vector<Guess> guess;
	static constexpr size_t kBlock = 16384;   // collapses judged together
	std::vector<std::pair<int, int>> edges;              // cheapest()'s
	std::vector<Collapse>            all, order;

	void index_faces()
	{
		start.assign(V.size() + 1, 0);
		for (const Tri& t : F)
			for (int v : t) ++start[v + 1];
		for (size_t v = 0; v < V.size(); ++v) start[v + 1] += start[v];
		incident.assign(start.back(), -1);
		std::vector<int> at(start.begin(), start.end() - 1);
		for (int f = 0; f < (int) F.size(); ++f)
			for (int v : F[f]) incident[at[v]++] = f;
		dead.assign(F.size(), 0);
	}

	void compact_faces()
	{
		size_t k = 0;
		for (size_t f = 0; f < F.size(); ++f)
			if (!dead[f]) F[k++] = F[f];
		F.resize(k);
	}

	// Where the merged vertex goes: the quadric's minimum when it is well defined and near the edge,
	// else the better end or the midpoint.
	Collapse measure(int u, int v) const
	{
		Quadric q = Q[u];
		q += Q[v];
		Collapse     c{INFINITY, u, v, V[u]};
		const double len = (V[u] - V[v]).norm();
		const Vec3   mid = 0.5 * (V[u] + V[v]);
		if (q.A.determinant() > 1e-9 * q.A.trace() * q.A.trace() * q.A.trace()) {
			const Vec3 p = -q.A.inverse() * q.b;
			if ((p - mid).norm() <= len) c = {q.mean(p), u, v, p};
		}
		for (const Vec3& p : {V[u], V[v], mid}) {
			const double cost = q.mean(p);
			if (cost < c.cost) c = {cost, u, v, p};
		}
		return c;
	}

	// Every edge's collapse within the error bar, cheapest first (into `order`; the buffers are kept
	// from round to round, as fresh ones of millions of entries cost more to zero than to fill).
	void cheapest()
	{
		edges.clear();
		for (const Tri& t : F)
			for (int k = 0; k < 3; ++k)
				if (t[k] < t[(k + 1) % 3]) edges.push_back({t[k], t[(k + 1) % 3]});
		all.resize(edges.size());
		parallel_for_chunked(edges.size(), 4096, [&](size_t i) { all[i] = measure(edges[i].first, edges[i].second); });
		order.clear();
		for (const Collapse& c : all)
			if (c.cost <= bar) order.push_back(c);
		sort_halves(order.begin(), order.end());   // a total order: cost, then the edge's ends
	}

	template <class Fn> void each_face(int v, Fn fn) const
	{
		for (int i = start[v]; i < start[v + 1]; ++i)
			if (!dead[incident[i]]) fn(incident[i]);
	}
	int degree(int v) const
	{
		int n = 0;
		each_face(v, [&](int) { ++n; });
		return n;
	}

	// The link condition (the two ends share exactly the edge's two opposite vertices, each left with
	// three neighbours at least) and no face turned or flattened. Reads the faces about c.u and c.v,
	// their vertices, and the faces about the two opposite vertices.
	Guess judge(const Collapse& c) const
	{
		thread_local Scratch s;   // each thread's, kept from call to call
		auto&                ring = s.ring;
		auto& opposite = s.opposite;
		for (auto& r : ring) r.clear();
		opposite.clear(), s.common.clear();
		for (int k = 0; k < 2; ++k)
			each_face(k ? c.v : c.u, [&](int f) {
				const Tri& t = F[f];
				const bool both = std::count(t.begin(), t.end(), c.u) && std::count(t.begin(), t.end(), c.v);
				for (int w : t) {
					if (w != c.u && w != c.v) ring[k].push_back(w);
					if (both && k == 0 && w != c.u && w != c.v) opposite.push_back(w);
				}
			});
		Guess g;
		if (opposite.size() != 2) return g;
		for (auto& r : ring) {
			std::sort(r.begin(), r.end());
			r.erase(std::unique(r.begin(), r.end()), r.end());
		}
		std::set_intersection(ring[0].begin(), ring[0].end(), ring[1].begin(), ring[1].end(), std::back_inserter(s.common));
		if (s.common.size() != 2 || ring[0].size() + ring[1].size() - 2 < 3) return g;
		g.opposite[0] = opposite[0], g.opposite[1] = opposite[1];
		for (int o : opposite)
			if (degree(o) < 4) return g;
		bool ok = true;
		for (int k = 0; k < 2 && ok; ++k)
			each_face(k ? c.v : c.u, [&](int f) {
				const Tri& t = F[f];
				if (std::count(t.begin(), t.end(), c.u) && std::count(t.begin(), t.end(), c.v)) return;
				std::array<Vec3, 3> p;
				for (int j = 0; j < 3; ++j) p[j] = t[j] == c.u || t[j] == c.v ? c.p : V[t[j]];
				const Vec3 before = (V[t[1]] - V[t[0]]).cross(V[t[2]] - V[t[0]]);
				const Vec3 after  = (p[1] - p[0]).cross(p[2] - p[0]);
				ok = ok && after.norm() > floor && after.dot(before) >= 0.5 * after.norm() * before.norm();
			});
		g.ok = ok;
		return g;
	}

	// Marks every vertex whose faces collapse(c) changes: those of the faces about c.u and c.v.
	void touch(const Collapse& c, int block)
	{
		for (int s = 0; s < 2; ++s)
			each_face(s ? c.v : c.u, [&](int f) {
				for (int w : F[f]) touched[w] = block;
			});
	}

	void collapse(const Collapse& c)
	{
		locked[c.u] = locked[c.v] = 1;   // u's face list is stale from here on (v's faces joined it)
		each_face(c.v, [&](int f) {
			Tri& t = F[f];
			if (std::count(t.begin(), t.end(), c.u)) dead[f] = 1;
			else
				for (int& w : t)
					if (w == c.v) w = c.u;
		});
		V[c.u] = c.p;
		Q[c.u] += Q[c.v];
	}
};

// The same surface in any pose, listed alike: where the shape's principal axes are its own
// (PoseFrame::distinct), its vertices are turned into that frame; then they are snapped to a grid of a
// power of two (about 1e-8 of the size; a rounding apart in two poses almost never straddles a step),
// so every pose measures and ties its collapses on the same numbers. `back` undoes it. (The faces
// stay the input's.)
struct Framed
{
	std::vector<Vec3> V;
	Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
	Vec3            centre = Vec3::Zero();
	double          step = 1;
	Vec3            back(const Vec3& p) const { return axes.transpose() * (step * p + centre); }
};

Framed framed(const TriMesh& m)
{
	Framed          f;
	const PoseFrame fr = pose_frame(m);
	if (fr.distinct(0) && fr.distinct(1) && fr.distinct(2)) f.axes = fr.axes;
	f.V.reserve(m.V.size());
	Eigen::AlignedBox3d box;
	for (const Vec3& p : m.V) box.extend(f.V.emplace_back(f.axes * p));
	f.centre = box.center();
	f.step   = std::ldexp(1.0, std::ilogb(std::max(box.diagonal().norm(), 1e-300)) - 26);
	for (Vec3& p : f.V) p = ((p - f.centre) / f.step).array().round().matrix();
	return f;
}

// The mesh (vertices V, faces F) listed in an order of its own: vertices by position (x, then y, then z; coincident ones in
// the order given), each face from its least vertex on (the same turn), faces sorted. Every order of
// the same surface's vertices and faces lists the same, so the collapses tie and sum alike.
TriMesh canonical(const std::vector<Vec3>& V, const std::vector<Tri>& F)
{
	std::vector<int> by(V.size());
	for (size_t i = 0; i < by.size(); ++i) by[i] = (int) i;
	std::stable_sort(by.begin(), by.end(), [&](int a, int b) {
		const Vec3 &p = V[a], &q = V[b];
		return std::make_tuple(p.x(), p.y(), p.z()) < std::make_tuple(q.x(), q.y(), q.z());
	});
	std::vector<int> rank(by.size());
	TriMesh          out;
	out.V.reserve(by.size());
	for (size_t i = 0; i < by.size(); ++i) rank[by[i]] = (int) i, out.V.push_back(V[by[i]]);
	out.F.reserve(F.size());
	for (const Tri& t : F) {
		Tri r = {rank[t[0]], rank[t[1]], rank[t[2]]};
		std::rotate(r.begin(), std::min_element(r.begin(), r.end()), r.end());
		out.F.push_back(r);
	}
	std::sort(out.F.begin(), out.F.end());
	return out;
}

} // namespace

Decimated decimate(const TriMesh& m, int target_faces, double max_error)
{
	Decimated    out;
	const Framed f = framed(m);
	Decimator    d(canonical(f.V, m.F), max_error / f.step);
	while (d.faces() > (size_t) std::max(target_faces, 4) && out.passes < 1000 && d.round(std::max(target_faces, 4))) ++out.passes;
	out.mesh = d.mesh();
	for (Vec3& p : out.mesh.V) p = f.back(p);
	return out;
}

} // namespace acd
