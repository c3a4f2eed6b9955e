#include "acd/solid/solid.h"
#include "acd/mesh/disjoint_sets.h"
#include "acd/mesh/measures.h"
#include "acd/mesh/parallel.h"
#include "acd/mesh/topology.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <climits>

namespace acd {

namespace {

[[noreturn]] void invalid(const std::string& msg, Error::Code code = Error::Unspecified, long count = 0)
{
	throw Error(Error::InvalidInput, msg, code, count);
}

// Orient every shell by how deeply it is nested (point in solid, not bounding boxes): even depth
// bounds material from outside (outward), odd depth is a cavity (inward). Shells given the wrong
// way round are turned. Bounding boxes only skip shells that cannot contain the probe point.
void orient_by_nesting(Solid& s, const std::vector<int>& comp, int ncomp)
{
	std::vector<TriMesh> shell(ncomp);
	for (int f = 0; f < (int) s.mesh.F.size(); ++f) shell[comp[f]].F.push_back(s.mesh.F[f]);
	std::vector<Eigen::AlignedBox3d> box(ncomp);
	for (int c = 0; c < ncomp; ++c) {
		shell[c].V = s.mesh.V;   // shared vertex array: inside() reads only the faces' corners
		for (const Tri& t : shell[c].F)
			for (int v : t) box[c].extend(s.mesh.V[v]);
	}
	std::vector<char> flip(ncomp, 0);
	for (int c = 0; c < ncomp; ++c) {
		// The shell's extreme vertices along each axis: all inside another shell means nested in it.
		std::array<Vec3, 6> probe;
		probe.fill(s.mesh.V[shell[c].F[0][0]]);
		for (const Tri& t : shell[c].F)
			for (int v : t)
				for (int k = 0; k < 3; ++k) {
					const Vec3& p = s.mesh.V[v];
					if (p[k] < probe[2 * k][k]) probe[2 * k] = p;
					if (p[k] > probe[2 * k + 1][k]) probe[2 * k + 1] = p;
				}
		int depth = 0;
		for (int o = 0; o < ncomp; ++o) {
			if (o == c || !box[o].contains(box[c])) continue;
			bool all = true;
			for (const Vec3& p : probe) all = all && inside(shell[o], p);
			depth += all;
		}
		const bool cavity = depth % 2 == 1;
		s.cavities += cavity;
		flip[c] = (signed_volume(shell[c]) > 0) == cavity;
		s.reoriented_shells += flip[c];
	}
	for (int f = 0; f < (int) s.mesh.F.size(); ++f)
		if (flip[comp[f]]) std::swap(s.mesh.F[f][1], s.mesh.F[f][2]);
	s.flipped = s.reoriented_shells > 0;
}

// make_solid's stages. Each refuses what it finds with the repair that fixes it.

// Coordinates finite, faces present, indices valid; the referenced vertices, compacted (s.mesh.V).
// Returns the map from input to compacted vertex ids.
std::vector<int> compact_vertices(const TriMesh& in, Solid& s)
{
	if (in.V.empty()) invalid("The mesh is empty: it has no vertices.");
	if (in.F.empty())
		invalid("The mesh is a point cloud (" + std::to_string(in.V.size()) +
		            " vertices, no faces); a closed surface is needed (alpha wrapping makes one).",
		        Error::PointCloud, (long) in.V.size());
	for (const Vec3& p : in.V)
		if (!p.allFinite()) invalid("The mesh has vertices with NaN or infinite coordinates.");
	std::vector<int> remap(in.V.size(), -1);
	for (const Tri& t : in.F)
		for (int k = 0; k < 3; ++k) {
			if (t[k] < 0 || t[k] >= (int) in.V.size()) invalid("A face references a missing vertex.");
			if (remap[t[k]] < 0) {
				remap[t[k]] = (int) s.mesh.V.size();
				s.mesh.V.push_back(in.V[t[k]]);
				s.source_vertex.push_back(t[k]);
			}
		}
	s.unreferenced_vertices = (int) (in.V.size() - s.mesh.V.size());
	return remap;
}

// The size, within the range the arithmetic can take.
double checked_size(const Solid& s)
{
	const double diag = bbox_diagonal(s.mesh.V);
	if (!(diag > 0) || !std::isfinite(diag)) invalid("The mesh is degenerate: all its vertices coincide.");
	// Coordinates so large that squared lengths overflow, or so small that they underflow.
	if (diag > 1e150 || diag < 1e-150)
		invalid("The mesh's size (bounding box diagonal " + std::to_string(diag) +
		        ") is outside the range the decomposition can compute with; rescale it.");
	return diag;
}

// The faces on compacted vertices (s.mesh.F): none repeating a vertex, of zero area, or twice.
void checked_faces(const TriMesh& in, const std::vector<int>& remap, Solid& s)
{
	int degenerate = 0, repeated = 0;
	for (const Tri& t : in.F) {
		Tri r{remap[t[0]], remap[t[1]], remap[t[2]]};
		if (r[0] == r[1] || r[1] == r[2] || r[0] == r[2]) {
			++repeated;
			continue;
		}
		const Vec3 &a = s.mesh.V[r[0]], &b = s.mesh.V[r[1]], &c = s.mesh.V[r[2]];
		if ((b - a).cross(c - a).squaredNorm() == 0) ++degenerate;
		s.mesh.F.push_back(r);
	}
	if (repeated > 0)
		invalid(std::to_string(repeated) + " faces repeat a vertex.", Error::RepeatedVertex, repeated);
	if (degenerate > 0)
		invalid(std::to_string(degenerate) + " faces have zero area.", Error::ZeroArea, degenerate);
	// Duplicated faces (same three vertices, either orientation) would otherwise be reported as
	// non-manifold or misoriented edges, which sends the user to the wrong repair.
	std::vector<Tri> keys(s.mesh.F);
	for (Tri& t : keys) std::sort(t.begin(), t.end());
	std::sort(keys.begin(), keys.end());
	const long dup = (long) (keys.end() - std::unique(keys.begin(), keys.end()));
	if (dup > 0)
		invalid(std::to_string(dup) + " faces duplicate other faces.", Error::DuplicateFaces, dup);
}

// Edge use: each undirected edge used by exactly two faces, once in each direction. Returns each
// corner's mate.
std::vector<int> check_edges(const TriMesh& m)
{
	EdgeUses   u        = edge_uses(m.F);
	const long boundary = u.boundary, nonmanifold = u.nonmanifold, misoriented = u.misoriented;
	if (boundary > 0)
		invalid("The mesh is open: it has " + std::to_string(boundary) +
		            " boundary edges. The decomposition needs a closed (watertight) solid (preprocessing 'auto' "
		            "welds or alpha-wraps it).",
		        Error::OpenMesh, boundary);
	if (nonmanifold > 0)
		invalid("The mesh has " + std::to_string(nonmanifold) +
		            " non-manifold edges (shared by more than two faces); preprocessing 'auto' repairs it.",
		        Error::NonManifoldEdges, nonmanifold);
	if (misoriented > 0)
		invalid("The mesh's faces are not consistently oriented (" + std::to_string(misoriented) +
		            " edges are used twice in the same direction).",
		        Error::Misoriented, misoriented);
	return std::move(u.mate);
}

// Split non-manifold vertices: walk each fan of corners around a vertex across its edges; a vertex
// reached by a second fan gets a copy of its own.
void split_vertex_fans(Solid& s, const std::vector<int>& mate)
{
	const std::vector<Tri> orig = s.mesh.F;
	const int              nf   = (int) orig.size();
	std::vector<char>      seen(nf * 3, 0);
	std::vector<char>      has_fan(s.mesh.V.size(), 0);
	for (int f = 0; f < nf; ++f)
		for (int k = 0; k < 3; ++k) {
			if (seen[f * 3 + k]) continue;
			const int v      = orig[f][k];
			int       target = v;
			if (has_fan[v]) {
				target = (int) s.mesh.V.size();
				s.mesh.V.push_back(s.mesh.V[v]);
				s.source_vertex.push_back(s.source_vertex[v]);
				++s.split_vertices;
			}
			has_fan[v] = 1;
			int cf = f, ck = k;
			while (!seen[cf * 3 + ck]) {
				seen[cf * 3 + ck] = 1;
				s.mesh.F[cf][ck]  = target;
				// this face's corner (ck + 2) holds the edge prev -> v; its mate, v -> prev, starts at v
				const int next = mate[3 * cf + (ck + 2) % 3];
				if (next < 0) break;
				cf = next / 3;
				ck = next % 3;
			}
		}
}

} // namespace

namespace {

// The crossing search's slabs: the faces in order of their boxes' low end along the longest axis
// (`order`), slab s owning order[s * size, (s + 1) * size) and searched with the faces up to end[s]
// that its boxes reach. One slab of everything when long faces would make the slabs overlap much.
struct Slabs
{
	std::vector<int>    order;
	std::vector<size_t> end;
	size_t              size = 0;
};

Slabs slabs_of(const TriMesh& m, size_t size)
{
	const size_t        nf = m.F.size();
	Eigen::AlignedBox3d box;
	for (const Vec3& p : m.V) box.extend(p);
	int axis = 0;
	box.sizes().maxCoeff(&axis);
	std::vector<std::pair<double, int>> low(nf);   // (box's low end, face)
	std::vector<double>                 high(nf);  // by face
	for (size_t f = 0; f < nf; ++f) {
		const Tri&   t = m.F[f];
		const double a = m.V[t[0]][axis], b = m.V[t[1]][axis], c = m.V[t[2]][axis];
		low[f]         = {std::min({a, b, c}), (int) f};
		high[f]        = std::max({a, b, c});
	}
	std::sort(low.begin(), low.end());
	Slabs s;
	s.size = size;
	for (const auto& l : low) s.order.push_back(l.second);
	size_t searched = 0;
	for (size_t first = 0; first < nf; first += size) {
		double reach = -INFINITY;
		for (size_t i = first; i < std::min(nf, first + size); ++i) reach = std::max(reach, high[low[i].second]);
		s.end.push_back((size_t) (std::upper_bound(low.begin(), low.end(), std::make_pair(reach, INT_MAX)) - low.begin()));
		searched += s.end.back() - first;
	}
	if (s.end.size() < 2 || searched > nf + nf / 2) s.end.assign(1, nf), s.size = nf;
	return s;
}

} // namespace

// Cuts assume the surface bounds one solid; overlapping or folded sheets can make parts that are not
// closed. Counted, not refused: scanned meshes often cross themselves a little (the host decides;
// the decomposition itself never returns an open part).
//
// A large mesh is searched in slabs on all cores (slabs_of). A pair is kept by the slab of its earlier
// face, so each is found once; the sorted pairs do not depend on the slabs.
std::vector<std::pair<int, int>> self_crossings(const TriMesh& m, double diag)
{
	using K = CGAL::Exact_predicates_inexact_constructions_kernel;
	std::vector<K::Point_3> pts;
	pts.reserve(m.V.size());
	for (const Vec3& p : m.V) pts.emplace_back(p.x(), p.y(), p.z());
	const Slabs                                                   slabs = slabs_of(m, 40000);
	std::vector<std::vector<std::pair<std::size_t, std::size_t>>> found(slabs.end.size());
	parallel_for(slabs.end.size(), [&](size_t s) {
		const size_t                            first = s * slabs.size, own = first + slabs.size;
		std::vector<std::array<std::size_t, 3>> tris;
		for (size_t i = first; i < slabs.end[s]; ++i) {
			const Tri& t = m.F[slabs.order[i]];
			tris.push_back({(std::size_t) t[0], (std::size_t) t[1], (std::size_t) t[2]});
		}
		std::vector<std::pair<std::size_t, std::size_t>> pairs;
		CGAL::Polygon_mesh_processing::triangle_soup_self_intersections(pts, tris, std::back_inserter(pairs));
		for (const auto& [i, j] : pairs)
			if (first + std::min(i, j) < own) found[s].push_back({(std::size_t) slabs.order[first + i], (std::size_t) slabs.order[first + j]});
	});
	// Faces that share a corner, or nearly do, may cross by a rounding error (tiny triangles of
	// earlier cuts do): not a fold of the surface.
	const double                     near2 = std::pow(1e-9 * diag, 2);
	std::vector<std::pair<int, int>> crossing;
	for (const auto& pairs : found)
		for (const auto& [f, g] : pairs) {
			bool touch = false;
			for (int a : m.F[f])
				for (int b : m.F[g]) touch |= a == b || (m.V[a] - m.V[b]).squaredNorm() <= near2;
			if (!touch) crossing.push_back({(int) std::min(f, g), (int) std::max(f, g)});
		}
	std::sort(crossing.begin(), crossing.end());
	return crossing;
}

namespace {

// Shells oriented by their nesting, the whole outward; refused if it holds no volume.
// `comp`: each face's shell (face_components).
void orient(Solid& s, double diag, const std::vector<int>& comp)
{
	// Nesting costs shells x faces ray tests; beyond a few hundred shells (debris, particle sets)
	// the shells keep their given orientation. Shells that cross each other have no nesting to go by.
	if (s.shells > 1 && s.shells <= 256 && s.self_intersections == 0) orient_by_nesting(s, comp, s.shells);
	s.volume = signed_volume(s.mesh);
	if (!(std::abs(s.volume) > 1e-12 * diag * diag * diag))
		invalid("The mesh encloses no volume (it is flat or its shells cancel out).");
	if (s.volume < 0) {
		// Consistently oriented but inside out (e.g. horse.ply as MeshLab reads it): flip it, and say so.
		for (Tri& t : s.mesh.F) std::swap(t[1], t[2]);
		s.volume  = -s.volume;
		s.flipped = true;
	}
}

} // namespace

Solid make_solid(const TriMesh& in, bool crossings)
{
	Solid                  s;
	const std::vector<int> remap = compact_vertices(in, s);
	const double           diag  = checked_size(s);
	checked_faces(in, remap, s);
	split_vertex_fans(s, check_edges(s.mesh));
	const std::vector<int> comp = face_components(s.mesh, &s.shells);
	s.self_intersections = -1;
	if (crossings || s.shells > 1) find_crossings(s);
	orient(s, diag, comp);
	return s;
}

void find_crossings(Solid& s)
{
	s.crossing_faces     = self_crossings(s.mesh, bbox_diagonal(s.mesh.V));
	s.self_intersections = (long) s.crossing_faces.size();
}

long crossings_off_cuts(const Solid& s, const std::vector<Plane>& cuts, double eps)
{
	const auto side = [&](const Tri& t, const Plane& pl) {
		double lo = INFINITY, hi = -INFINITY;
		for (int v : t) lo = std::min(lo, pl.eval(s.mesh.V[v])), hi = std::max(hi, pl.eval(s.mesh.V[v]));
		if (hi <= eps && lo >= -eps) {   // a face in the plane: on its solid's side
			const Vec3& A = s.mesh.V[t[0]];
			return pl.n.dot((s.mesh.V[t[1]] - A).cross(s.mesh.V[t[2]] - A)) > 0 ? -1 : 1;
		}
		return hi <= eps ? -1 : lo >= -eps ? 1 : 0;
	};
	long n = 0;
	for (const auto& [f, g] : s.crossing_faces) {
		bool apart = false;
		for (const Plane& pl : cuts) {
			const int a = side(s.mesh.F[f], pl), b = side(s.mesh.F[g], pl);
			apart |= a != 0 && b != 0 && a != b;
		}
		n += !apart;
	}
	return n;
}

} // namespace acd
