#include "acd/polygon/polygon.h"
#include "acd/polygon/geometry2.h"
#include "acd/mesh/measures.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <vector>

namespace acd {

namespace {

// Directed boundary edges: of the faces (an edge whose reverse is not used), else the edges.
std::vector<Edge> boundary_edges(const std::vector<Vec3>& V, const std::vector<Tri>& F, const std::vector<Edge>& E)
{
	std::vector<Edge> boundary;
	if (!F.empty()) {
		std::set<std::pair<int, int>> directed;
		for (const Tri& t : F)
			for (int k = 0; k < 3; ++k) directed.insert({t[k], t[(k + 1) % 3]});
		for (const auto& [a, b] : directed)
			if (!directed.count({b, a})) boundary.push_back({a, b});
		if (boundary.empty()) invalid("The mesh has no boundary: a closed surface is not a planar polygon.");
	}
	else boundary = E;
	if (boundary.empty()) invalid("The layer has neither faces nor edges: nothing outlines a polygon.");
	for (const Edge& e : boundary)
		if (e[0] < 0 || e[1] < 0 || e[0] >= (int) V.size() || e[1] >= (int) V.size() || e[0] == e[1])
			invalid("An edge has an invalid vertex index.");
	return boundary;
}

// Chain the edges into loops of vertex ids. Faces give directions; bare edges (`directed` false) are
// undirected (each vertex on two).
std::vector<std::vector<int>> chain_loops(const std::vector<Edge>& boundary, bool directed)
{
	std::map<int, std::vector<int>> link;
	for (const Edge& e : boundary) {
		link[e[0]].push_back(e[1]);
		if (!directed) link[e[1]].push_back(e[0]);
	}
	for (const auto& [v, out] : link) {
		if (out.size() == (directed ? 1u : 2u)) continue;
		if (!directed)
			invalid("The edges do not form closed loops: a vertex has " + std::to_string(out.size()) +
			        " edges (each needs exactly 2).");
		throw Error(Error::InvalidInput, "The mesh's boundary touches itself at a vertex (non-manifold boundary).",
		            Error::NonManifoldBoundary);
	}
	std::set<int>                 used;
	std::vector<std::vector<int>> loops;
	for (const auto& [start, out] : link) {
		if (used.count(start)) continue;
		std::vector<int> L;
		int              prev = -1, v = start;
		do {
			used.insert(v);
			L.push_back(v);
			const std::vector<int>& nx = link[v];
			const int next = nx.size() == 1 || nx[0] != prev ? nx[0] : nx[1];
			prev = v;
			v    = next;
			if (!link.count(v)) invalid("The boundary edges do not close into loops.");
		} while (v != start && L.size() <= link.size());
		if (v != start) invalid("The boundary edges do not close into loops.");
		loops.push_back(std::move(L));
	}
	return loops;
}

// The plane's frame from the principal axes of the points; with faces, their side is the front (loops
// then come out counter-clockwise). Refused unless the points are planar to 1e-6 of their size.
void fit_plane(const std::vector<Vec3>& pts, const std::vector<Vec3>& V, const std::vector<Tri>& F, PlanarLoops& out)
{
	for (const Vec3& p : pts) out.origin += p;
	out.origin /= (double) pts.size();
	Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
	for (const Vec3& p : pts) C += (p - out.origin) * (p - out.origin).transpose();
	Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
	out.n = es.eigenvectors().col(0);
	out.u = es.eigenvectors().col(2);
	if (!F.empty()) {
		Vec3 sum = Vec3::Zero();
		for (const Tri& t : F) sum += (V[t[1]] - V[t[0]]).cross(V[t[2]] - V[t[0]]);
		if (sum.dot(out.n) < 0) out.n = -out.n;
	}
	out.w = out.n.cross(out.u);
	const double size = extent(pts);
	if (!(size > 0)) invalid("The polygon is degenerate: all its points coincide.");
	double off = 0;
	for (const Vec3& p : pts) off = std::max(off, std::abs(out.n.dot(p - out.origin)));
	if (off > 1e-6 * size)
		invalid("The outline is not planar (a point lies " + std::to_string(off / size) +
		        " of the size off its best-fitting plane); the polygon filter needs a planar layer.");
}

} // namespace

PlanarLoops planar_loops(const std::vector<Vec3>& V, const std::vector<Tri>& F, const std::vector<Edge>& E)
{
	const std::vector<std::vector<int>> index_loops = chain_loops(boundary_edges(V, F, E), !F.empty());
	std::vector<Vec3>                   pts;
	for (const auto& L : index_loops)
		for (int v : L) {
			if (!V[v].allFinite()) invalid("The polygon has NaN or infinite coordinates.");
			pts.push_back(V[v]);
		}
	PlanarLoops out;
	fit_plane(pts, V, F, out);
	for (const auto& L : index_loops) {
		Loop2 l;
		for (int v : L) l.emplace_back(out.u.dot(V[v] - out.origin), out.w.dot(V[v] - out.origin));
		out.loops.push_back(std::move(l));
	}
	return out;
}

} // namespace acd
