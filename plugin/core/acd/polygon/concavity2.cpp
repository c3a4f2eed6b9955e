#include "acd/polygon/polygon.h"
#include "acd/polygon/geometry2.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <vector>

namespace acd {

namespace {

// Convex hull of a loop (Andrew's monotone chain, strictly convex corners) as indices, counter-clockwise.
std::vector<int> hull_indices(const Loop2& P)
{
	const int n = (int) P.size();
	std::vector<int> idx(n);
	std::iota(idx.begin(), idx.end(), 0);
	std::sort(idx.begin(), idx.end(), [&](int i, int j) {
		return P[i].x() < P[j].x() || (P[i].x() == P[j].x() && P[i].y() < P[j].y());
	});
	auto turn = [&](int o, int a, int b) {
		return CGAL::orientation(K::Point_2(P[o].x(), P[o].y()), K::Point_2(P[a].x(), P[a].y()),
		                         K::Point_2(P[b].x(), P[b].y()));
	};
	std::vector<int> hull(2 * n);
	int              k = 0;
	for (int i = 0; i < n; ++i) {
		while (k >= 2 && turn(hull[k - 2], hull[k - 1], idx[i]) != CGAL::LEFT_TURN) --k;
		hull[k++] = idx[i];
	}
	for (int i = n - 2, t = k + 1; i >= 0; --i) {
		while (k >= t && turn(hull[k - 2], hull[k - 1], idx[i]) != CGAL::LEFT_TURN) --k;
		hull[k++] = idx[i];
	}
	hull.resize(k - 1);
	return hull;
}

} // namespace

Concavity2 measure_concavity(const Polygon2& p)
{
	const Loop2& P = p.outer;
	const int    n = (int) P.size();
	Concavity2   r;
	r.outer.assign(n, 0.0);
	const double flat = 1e-9 * extent2(P);

	const std::vector<int> hull = hull_indices(P);

	// Bridges: consecutive hull vertices that are not consecutive on the boundary; the vertices
	// between them form the pocket, measured to the bridge's line (Algorithm 5.1).
	const int h = (int) hull.size();
	for (int i = 0; i < h; ++i) {
		const int a = hull[i], b = hull[(i + 1) % h];
		if ((b - a + n) % n <= 1) continue;
		++r.bridges;
		const Vec2 e = (P[b] - P[a]).normalized();
		for (int v = (a + 1) % n; v != b; v = (v + 1) % n) r.outer[v] = std::max(0.0, cross(e, P[v] - P[a]));
	}
	for (int v = 0; v < n; ++v) {
		const Vec2 &prev = P[(v + n - 1) % n], &cur = P[v], &next = P[(v + 1) % n];
		const Vec2  chord = next - prev;
		// reflex: the corner lies clearly left of its neighbours' chord (inside a counter-clockwise loop)
		if (chord.norm() > 0 && cross(chord.normalized(), cur - prev) > flat) {
			++r.notches;
			if (r.outer[v] > r.max_concavity || r.max_vertex < 0) {
				r.max_concavity = r.outer[v];
				r.max_vertex    = v;
			}
		}
	}
	// A hole's depth: its deepest vertex's distance to the hull's boundary.
	for (const Loop2& H : p.holes) {
		double deepest = 0;
		for (const Vec2& q : H) {
			double d = HUGE_VAL;
			for (int i = 0; i < h; ++i) {
				const Vec2& a = P[hull[i]];
				d = std::min(d, cross((P[hull[(i + 1) % h]] - a).normalized(), q - a));
			}
			deepest = std::max(deepest, d);
		}
		r.hole_depth.push_back(deepest);
	}
	return r;
}

} // namespace acd
