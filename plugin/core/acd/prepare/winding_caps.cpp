#include "acd/prepare/winding_caps.h"
#include "acd/mesh/measures.h"
#include "acd/mesh/parallel.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace acd {

namespace {

// The six tetrahedra of a cube about its diagonal 0-7 (corner bits: x 1, y 2, z 4); they share faces
// with the neighbouring cubes' tetrahedra, so the level set has no cracks.
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

struct Grid
{
	Vec3   lo;
	double h = 0;
	long   n[3] = {0, 0, 0};
	long   id(long i, long j, long k) const { return i + n[0] * (j + n[1] * k); }
	Vec3   at(long g) const { return lo + h * Vec3(g % n[0], (g / n[0]) % n[1], g / (n[0] * n[1])); }
	size_t size() const { return size_t(n[0] * n[1] * n[2]); }
};

Grid make_grid(const TriMesh& in, double spacing, size_t max_points)
{
	const Eigen::AlignedBox3d box = finite_box(in);
	Grid                      g;
	g.h = spacing;
	for (;;) {
		g.lo = box.min() - Vec3::Constant(2 * g.h);
		for (int a = 0; a < 3; ++a) g.n[a] = (long) std::ceil((box.max()[a] - box.min()[a]) / g.h) + 5;
		if (g.size() <= max_points) return g;
		g.h *= 1.05 * std::cbrt(double(g.size()) / max_points);
	}
}

// The vertices of edges that only one face uses: where the openings' caps begin.
std::vector<int> rim_vertices(const TriMesh& m)
{
	std::vector<std::pair<int, int>> edges;
	for (const Tri& t : m.F)
		for (int k = 0; k < 3; ++k) edges.push_back(std::minmax(t[k], t[(k + 1) % 3]));
	std::sort(edges.begin(), edges.end());
	std::vector<int> rim;
	for (size_t i = 0; i < edges.size();) {
		size_t j = i;
		while (j < edges.size() && edges[j] == edges[i]) ++j;
		if (j - i == 1) rim.push_back(edges[i].first), rim.push_back(edges[i].second);
		i = j;
	}
	return rim;
}

// |w| - 1/2 at the grid's points where the level set may pass, NaN elsewhere. First at the corners of
// blocks of kBlock^3 cells; then at every point of the blocks whose corners differ in sign or that hold
// a rim, and of their neighbours. Far from the input and its openings nothing is evaluated.
constexpr long kBlock = 2;
std::vector<double> sparse_values(const Grid& g, const TriMesh& input, const WindingNumber& wn)
{
	std::vector<double> f(g.size(), NAN);
	const auto          evaluate = [&](std::vector<long> ids) {
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        parallel_for_chunked(ids.size(), 256, [&](size_t i) { f[ids[i]] = std::abs(wn.at(g.at(ids[i]))) - 0.5; });
	};
	long nb[3];
	for (int a = 0; a < 3; ++a) nb[a] = (g.n[a] - 2) / kBlock + 1;
	const auto at = [&](long b, int a) { return std::min(b * kBlock, g.n[a] - 1); };
	std::vector<long> ids;
	for (long k = 0; k <= nb[2]; ++k)
		for (long j = 0; j <= nb[1]; ++j)
			for (long i = 0; i <= nb[0]; ++i) ids.push_back(g.id(at(i, 0), at(j, 1), at(k, 2)));
	evaluate(ids);
	const auto        block = [&](long i, long j, long k) { return i + nb[0] * (j + nb[1] * k); };
	std::vector<char> mark(size_t(nb[0] * nb[1] * nb[2]), 0);
	for (long k = 0; k < nb[2]; ++k)
		for (long j = 0; j < nb[1]; ++j)
			for (long i = 0; i < nb[0]; ++i) {
				int in = 0;
				for (int b = 0; b < 8; ++b)
					in += f[g.id(at(i + (b & 1), 0), at(j + ((b >> 1) & 1), 1), at(k + ((b >> 2) & 1), 2))] >= 0;
				mark[block(i, j, k)] = in > 0 && in < 8;
			}
	for (int v : rim_vertices(input)) {
		if (v < 0 || v >= (int) input.V.size() || !input.V[v].allFinite()) continue;
		const Vec3 p = (input.V[v] - g.lo) / (g.h * kBlock);
		mark[block(std::clamp((long) p.x(), 0L, nb[0] - 1), std::clamp((long) p.y(), 0L, nb[1] - 1),
		           std::clamp((long) p.z(), 0L, nb[2] - 1))] = 1;
	}
	ids.clear();
	for (long k = 0; k < nb[2]; ++k)
		for (long j = 0; j < nb[1]; ++j)
			for (long i = 0; i < nb[0]; ++i) {
				bool near_mark = false;
				for (long dk = -1; dk <= 1; ++dk)
					for (long dj = -1; dj <= 1; ++dj)
						for (long di = -1; di <= 1; ++di) {
							const long a = i + di, b = j + dj, c = k + dk;
							near_mark = near_mark || (a >= 0 && b >= 0 && c >= 0 && a < nb[0] && b < nb[1] &&
							                          c < nb[2] && mark[block(a, b, c)]);
						}
				if (!near_mark) continue;
				for (long z = k * kBlock; z <= at(k + 1, 2); ++z)
					for (long y = j * kBlock; y <= at(j + 1, 1); ++y)
						for (long x = i * kBlock; x <= at(i + 1, 0); ++x)
							if (std::isnan(f[g.id(x, y, z)])) ids.push_back(g.id(x, y, z));
			}
	evaluate(ids);
	return f;
}

// Marching tetrahedra over the values f (inside: f >= 0; NaN: not evaluated, no level set there); a
// vertex per crossed grid edge.
TriMesh level_set(const Grid& g, const std::vector<double>& f)
{
	TriMesh                             out;
	std::unordered_map<uint64_t, int>   on_edge;
	const auto vertex = [&](long a, long b) {
		if (a > b) std::swap(a, b);
		const uint64_t key = uint64_t(a) * g.size() + uint64_t(b);
		auto [it, added]   = on_edge.emplace(key, (int) out.V.size());
		if (added) out.V.push_back(g.at(a) + f[a] / (f[a] - f[b]) * (g.at(b) - g.at(a)));
		return it->second;
	};
	for (long k = 0; k + 1 < g.n[2]; ++k)
		for (long j = 0; j + 1 < g.n[1]; ++j)
			for (long i = 0; i + 1 < g.n[0]; ++i) {
				long c[8];
				int  in = 0, known = 0;
				for (int b = 0; b < 8; ++b) {
					c[b] = g.id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
					in += f[c[b]] >= 0;
					known += !std::isnan(f[c[b]]);
				}
				if (known < 8 || in == 0 || in == 8) continue;
				for (const auto& t : kTets) {
					long ins[4], outs[4];
					int  ni = 0, no = 0;
					for (int v : t) (f[c[v]] >= 0 ? ins[ni++] : outs[no++]) = c[v];
					if (ni == 1 || ni == 3) {
						const long  a = ni == 1 ? ins[0] : outs[0];
						const long* o = ni == 1 ? outs : ins;
						out.F.push_back({vertex(a, o[0]), vertex(a, o[1]), vertex(a, o[2])});
					}
					else if (ni == 2) {
						const int ac = vertex(ins[0], outs[0]), ad = vertex(ins[0], outs[1]);
						const int bc = vertex(ins[1], outs[0]), bd = vertex(ins[1], outs[1]);
						out.F.push_back({ac, ad, bd});
						out.F.push_back({ac, bd, bc});
					}
				}
			}
	return out;
}

} // namespace

WindingCaps winding_caps(const TriMesh& input, const WindingNumber& wn, const NearestOnSurface& near,
                         double spacing, size_t max_points)
{
	WindingCaps caps;
	const Grid  g = make_grid(input, spacing, max_points);
	caps.spacing  = g.h;
	TriMesh m = level_set(g, sparse_values(g, input, wn));

	// Near the input the level set is the input itself, blurred by the grid: move it back onto it.
	const double        snap = std::sqrt(3.0) * g.h;
	std::vector<char>   moved(m.V.size(), 0);
	std::vector<double> off(m.V.size(), 0);
	parallel_for_chunked(m.V.size(), 1024, [&](size_t i) {
		const Vec3 c = near.closest(m.V[i]);
		off[i]       = (c - m.V[i]).norm();
		if (off[i] <= snap) m.V[i] = c, moved[i] = 1, off[i] = 0;
	});
	caps.reach = m.V.empty() ? 0 : *std::max_element(off.begin(), off.end());
	// Faces moved onto the input entirely add nothing to it: the caps are the rest.
	double away = 0, all = 0;
	for (const Tri& t : m.F) {
		const double a = (m.V[t[1]] - m.V[t[0]]).cross(m.V[t[2]] - m.V[t[0]]).norm() / 2;
		all += a;
		if (!moved[t[0]] && !moved[t[1]] && !moved[t[2]]) away += a;
		if (a > 1e-12 * g.h * g.h && !(moved[t[0]] && moved[t[1]] && moved[t[2]])) caps.mesh.F.push_back(t);
	}
	caps.mesh.V   = std::move(m.V);
	caps.cap_share = all > 0 ? away / all : 0;
	return caps;
}

} // namespace acd
