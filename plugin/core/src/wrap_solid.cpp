#include "acd/wrap_solid.h"

#include "acd/preprocess.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <unordered_map>

namespace acd {

TriMesh weld(const TriMesh& in, double eps, int* merged)
{
	struct CellHash
	{
		size_t operator()(const std::array<long long, 3>& c) const
		{
			return std::hash<long long>()(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
		}
	};
	std::unordered_map<std::array<long long, 3>, std::vector<int>, CellHash> grid;
	TriMesh          out;
	std::vector<int> to(in.V.size(), -1);
	int              n = 0;
	for (size_t i = 0; i < in.V.size(); ++i) {
		const Vec3& p = in.V[i];
		if (!p.allFinite()) {   // kept apart: make_solid names them
			to[i] = (int) out.V.size();
			out.V.push_back(p);
			continue;
		}
		const std::array<long long, 3> c{(long long) std::floor(p.x() / eps), (long long) std::floor(p.y() / eps),
		                                 (long long) std::floor(p.z() / eps)};
		for (int dx = -1; dx <= 1 && to[i] < 0; ++dx)
			for (int dy = -1; dy <= 1 && to[i] < 0; ++dy)
				for (int dz = -1; dz <= 1 && to[i] < 0; ++dz) {
					auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
					if (it == grid.end()) continue;
					for (int j : it->second)
						if ((out.V[j] - p).norm() <= eps) { to[i] = j; ++n; break; }
				}
		if (to[i] < 0) {
			to[i] = (int) out.V.size();
			grid[c].push_back(to[i]);
			out.V.push_back(p);
		}
	}
	for (const Tri& t : in.F) {
		bool ok = true;
		for (int v : t) ok = ok && v >= 0 && v < (int) in.V.size();
		if (!ok) { out.F.push_back(t); continue; }   // left for make_solid to name
		const Tri w{to[t[0]], to[t[1]], to[t[2]]};
		if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) continue;
		out.F.push_back(w);
	}
	// Faces the welding made identical (same corners, same turn) are one face.
	std::vector<std::pair<std::array<int, 3>, int>> keys;
	for (int f = 0; f < (int) out.F.size(); ++f) {
		Tri t = out.F[f];
		std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
		keys.push_back({{t[0], t[1], t[2]}, f});
	}
	std::sort(keys.begin(), keys.end());
	std::vector<char> drop(out.F.size(), 0);
	for (size_t k = 1; k < keys.size(); ++k) drop[keys[k].second] = keys[k].first == keys[k - 1].first;
	std::vector<Tri> kept;
	for (size_t f = 0; f < out.F.size(); ++f)
		if (!drop[f]) kept.push_back(out.F[f]);
	out.F = std::move(kept);
	if (merged) *merged = n;
	return out;
}

std::vector<double> winding_numbers(const TriMesh& surface, const std::vector<Vec3>& points)
{
	std::vector<double> w(points.size(), 0.0);
	for (size_t i = 0; i < points.size(); ++i) {
		double sum = 0;   // solid angles, Van Oosterom and Strackee's formula
		for (const Tri& t : surface.F) {
			const Vec3   a = surface.V[t[0]] - points[i], b = surface.V[t[1]] - points[i], c = surface.V[t[2]] - points[i];
			const double la = a.norm(), lb = b.norm(), lc = c.norm();
			const double num = a.dot(b.cross(c));
			const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
			if (std::isfinite(num) && std::isfinite(den)) sum += 2 * std::atan2(num, den);
		}
		w[i] = sum / (4 * M_PI);
	}
	return w;
}

namespace {

// Points of the input's bounding box that its winding number places inside (|w| > 1/2: the input's
// orientation is not trusted), drawn from a fixed seed so that the choice is repeatable.
std::vector<Vec3> interior_samples(const TriMesh& in, int count)
{
	Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
	for (const Tri& t : in.F)
		for (int v : t)
			if (v >= 0 && v < (int) in.V.size() && in.V[v].allFinite()) {
				lo = lo.cwiseMin(in.V[v]);
				hi = hi.cwiseMax(in.V[v]);
			}
	std::vector<Vec3> pts;
	if (!(lo.array() <= hi.array()).all()) return pts;
	std::mt19937                           rng(12345);
	std::uniform_real_distribution<double> u(0.0, 1.0);
	for (int i = 0; i < count; ++i) pts.push_back(lo + (hi - lo).cwiseProduct(Vec3(u(rng), u(rng), u(rng))));
	TriMesh finite;   // faces with a vertex out of range or not finite do not count
	finite.V = in.V;
	for (const Tri& t : in.F) {
		bool ok = true;
		for (int v : t) ok = ok && v >= 0 && v < (int) in.V.size() && in.V[v].allFinite();
		if (ok) finite.F.push_back(t);
	}
	const std::vector<double> w = winding_numbers(finite, pts);
	std::vector<Vec3>         inside;
	for (size_t i = 0; i < pts.size(); ++i)
		if (std::abs(w[i]) > 0.5) inside.push_back(pts[i]);
	return inside;
}

double share_inside(const TriMesh& wrap, const std::vector<Vec3>& pts)
{
	if (pts.empty()) return 1;
	const std::vector<double> w = winding_numbers(wrap, pts);
	int                       n = 0;
	for (double x : w) n += x > 0.5;
	return double(n) / pts.size();
}

} // namespace

WrapSolidResult wrap_solid(const TriMesh& input, double alpha, double offset, double max_alpha, double min_inside)
{
	WrapSolidResult r;
	try {
		r.solid = make_solid(input);
		r.mesh  = input;
		return r;
	} catch (const Error& e) {
		if (e.kind != Error::InvalidInput) throw;
		r.reason = e.what();
	}
	{
		std::vector<Vec3> finite;
		for (const Vec3& p : input.V)
			if (p.allFinite()) finite.push_back(p);
		const double size = finite.empty() ? 0 : extent(finite);
		int          merged = 0;
		if (size > 0) try {
				TriMesh w = weld(input, 1e-5 * size, &merged);
				if (merged > 0) {
					Solid s = make_solid(w);
					if (s.self_intersections == 0) {
						r.mesh   = std::move(w);
						r.welded = merged;
						r.solid  = std::move(s);
						return r;
					}
				}
			} catch (const Error& e) {
				if (e.kind != Error::InvalidInput) throw;
			}
	}
	// Too few interior samples (a point cloud, a sheet, faces that cancel) cannot tell a skin from a
	// solid: the first wrap is kept. So is it when no wrap up to max_alpha holds the interior: the
	// input is then an open shell (a cover, a fairing) rather than a solid with small holes, and its
	// faithful skin is nearer to it than any coarse blob.
	const std::vector<Vec3> inside = interior_samples(input, 512);
	const bool              judge  = inside.size() >= 16;
	r.wrapped = true;
	for (double a = alpha;; a *= 2) {
		TriMesh      w     = alpha_wrap(input, a, offset);
		const double share = judge ? share_inside(w, inside) : 1.0;
		++r.tries;
		if (r.tries == 1 || share >= min_inside) r = WrapSolidResult{std::move(w), true, 0, a, share, r.tries, r.reason, std::nullopt};
		if (share >= min_inside || a * 2 > max_alpha * (1 + 1e-9)) break;
	}
	return r;
}

} // namespace acd
