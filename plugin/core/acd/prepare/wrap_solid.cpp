#include "acd/prepare/wrap_solid.h"

#include "acd/prepare/alpha_wrap.h"
#include "acd/mesh/measures.h"
#include "acd/solid/solid.h"
#include "acd/mesh/weld.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <unordered_map>

namespace acd {

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
		r.reason       = e.what();
		r.reason_code  = e.code;
		r.reason_count = e.count;
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
		if (r.tries == 1 || share >= min_inside) r = WrapSolidResult{std::move(w), true, 0, a, share, r.tries, r.reason, r.reason_code, r.reason_count, std::nullopt};
		if (share >= min_inside || a * 2 > max_alpha * (1 + 1e-9)) break;
	}
	return r;
}

} // namespace acd
