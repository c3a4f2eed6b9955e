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


// Segments of all loops cross or touch anywhere but at shared loop corners? Sweep by x with exact
// predicates (CGAL's filtered kernel).
bool loops_cross(const std::vector<Loop2>& loops)
{
	struct Seg
	{
		K::Segment_2 s;
		int          loop, i;
		double       lo, hi;
	};
	std::vector<Seg> segs;
	for (int l = 0; l < (int) loops.size(); ++l)
		for (int i = 0; i < (int) loops[l].size(); ++i) {
			const Vec2 &a = loops[l][i], &b = loops[l][(i + 1) % loops[l].size()];
			segs.push_back({K::Segment_2(K::Point_2(a.x(), a.y()), K::Point_2(b.x(), b.y())), l, i,
			                std::min(a.x(), b.x()), std::max(a.x(), b.x())});
		}
	std::sort(segs.begin(), segs.end(), [](const Seg& a, const Seg& b) { return a.lo < b.lo; });
	for (size_t i = 0; i < segs.size(); ++i)
		for (size_t j = i + 1; j < segs.size() && segs[j].lo <= segs[i].hi; ++j) {
			const Seg &a = segs[i], &b = segs[j];
			if (a.loop == b.loop) {
				const int n = (int) loops[a.loop].size();
				const bool ab = (a.i + 1) % n == b.i, ba = (b.i + 1) % n == a.i;
				if (ab || ba) {
					// Neighbours share corner m; they overlap only if they fold back onto each other.
					const Seg& s1 = ab ? a : b;
					const Seg& s2 = ab ? b : a;
					const auto &p = s1.s.source(), &m = s1.s.target(), &q = s2.s.target();
					if (CGAL::orientation(p, m, q) == CGAL::COLLINEAR && CGAL::angle(p, m, q) == CGAL::ACUTE) return true;
					if (n > 3 || !(ab && ba)) continue;
				}
			}
			if (CGAL::do_intersect(a.s, b.s)) return true;
		}
	return false;
}

Loop2 cleaned(const Loop2& in, double tol)
{
	Loop2 out;
	for (const Vec2& p : in)
		if (out.empty() || (p - out.back()).norm() > tol) out.push_back(p);
	while (out.size() > 1 && (out.front() - out.back()).norm() <= tol) out.pop_back();
	return out;
}

} // namespace

std::vector<Polygon2> polygons_from_loops(std::vector<Loop2> loops)
{
	if (loops.empty()) invalid("The polygon has no boundary loop.");
	Loop2 all;
	for (const Loop2& l : loops)
		for (const Vec2& p : l) {
			if (!p.allFinite()) invalid("The polygon has NaN or infinite coordinates.");
			all.push_back(p);
		}
	if (all.size() < 3) invalid("The polygon has fewer than 3 points.");
	const double size = extent2(all);
	if (!(size > 0)) invalid("The polygon is degenerate: all its points coincide.");
	for (Loop2& l : loops) {
		l = cleaned(l, 1e-12 * size);
		if (l.size() < 3) invalid("A boundary loop has fewer than 3 distinct points.");
	}
	if (loops_cross(loops))
		invalid("The boundary loops cross or touch themselves or each other; a polygon's outer boundary and "
		        "holes must be simple and disjoint.");
	for (const Loop2& l : loops)
		if (!(std::abs(signed_area(l)) > 1e-14 * size * size)) invalid("A boundary loop encloses no area.");

	// Nesting by point in polygon (loops do not cross, so one point of a loop decides).
	const int           n = (int) loops.size();
	std::vector<int>    depth(n, 0), parent(n, -1);
	std::vector<double> a(n);
	for (int i = 0; i < n; ++i) a[i] = std::abs(signed_area(loops[i]));
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j)
			if (i != j && inside(loops[j], loops[i][0])) {
				++depth[i];
				if (parent[i] < 0 || a[j] < a[parent[i]]) parent[i] = j;
			}
	std::vector<Polygon2> out;
	std::vector<int>      index(n, -1);
	for (int i = 0; i < n; ++i)
		if (depth[i] % 2 == 0) {
			if (signed_area(loops[i]) < 0) std::reverse(loops[i].begin(), loops[i].end());
			index[i] = (int) out.size();
			out.push_back({loops[i], {}});
		}
	for (int i = 0; i < n; ++i)
		if (depth[i] % 2 == 1) {
			if (signed_area(loops[i]) > 0) std::reverse(loops[i].begin(), loops[i].end());
			out[index[parent[i]]].holes.push_back(loops[i]);
		}
	// Largest first, as the 3D solids.
	std::stable_sort(out.begin(), out.end(), [](const Polygon2& x, const Polygon2& y) { return area(x) > area(y); });
	return out;
}

} // namespace acd
