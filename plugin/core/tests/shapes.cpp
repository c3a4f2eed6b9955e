#include "shapes.h"
#include "acd/mesh/measures.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace shapes {

TriMesh box(Vec3 lo, Vec3 hi)
{
	std::vector<Eigen::Vector2d> sq{{lo.x(), lo.y()}, {hi.x(), lo.y()}, {hi.x(), hi.y()}, {lo.x(), hi.y()}};
	return extrude(sq, lo.z(), hi.z());
}

// Ear clipping of a simple CCW polygon (small test polygons only).
static std::vector<std::array<int, 3>> ear_clip(const std::vector<Eigen::Vector2d>& p)
{
	std::vector<int>                 idx;
	std::vector<std::array<int, 3>> out;
	for (int i = 0; i < (int) p.size(); ++i) idx.push_back(i);
	auto cross = [](Eigen::Vector2d a, Eigen::Vector2d b, Eigen::Vector2d c) {
		return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
	};
	while (idx.size() > 3) {
		bool clipped = false;
		for (size_t i = 0; i < idx.size() && !clipped; ++i) {
			int a = idx[(i + idx.size() - 1) % idx.size()], b = idx[i], c = idx[(i + 1) % idx.size()];
			if (cross(p[a], p[b], p[c]) <= 0) continue;
			bool empty = true;
			for (int j : idx) {
				if (j == a || j == b || j == c) continue;
				if (cross(p[a], p[b], p[j]) >= 0 && cross(p[b], p[c], p[j]) >= 0 && cross(p[c], p[a], p[j]) >= 0)
					empty = false;
			}
			if (!empty) continue;
			out.push_back({a, b, c});
			idx.erase(idx.begin() + i);
			clipped = true;
		}
		if (!clipped) break;
	}
	if (idx.size() == 3) out.push_back({idx[0], idx[1], idx[2]});
	return out;
}

TriMesh extrude(const std::vector<Eigen::Vector2d>& poly, double z0, double z1)
{
	TriMesh    m;
	const int n = (int) poly.size();
	for (auto& q : poly) m.V.emplace_back(q.x(), q.y(), z0);
	for (auto& q : poly) m.V.emplace_back(q.x(), q.y(), z1);
	for (auto t : ear_clip(poly)) {
		m.F.push_back({t[0], t[2], t[1]});               // bottom faces down
		m.F.push_back({t[0] + n, t[1] + n, t[2] + n});   // top faces up
	}
	for (int i = 0; i < n; ++i) {
		int j = (i + 1) % n;
		m.F.push_back({i, j, j + n});
		m.F.push_back({i, j + n, i + n});
	}
	return m;
}

TriMesh sphere(int subdivisions, double radius)
{
	const double t = (1 + std::sqrt(5.0)) / 2;
	TriMesh      m;
	m.V = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
	       {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
	m.F = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
	       {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
	       {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
	for (int s = 0; s < subdivisions; ++s) {
		std::map<std::pair<int, int>, int> mid;
		auto midpoint = [&](int a, int b) {
			auto key = std::make_pair(std::min(a, b), std::max(a, b));
			auto it  = mid.find(key);
			if (it != mid.end()) return it->second;
			m.V.push_back((m.V[a] + m.V[b]) / 2);
			return mid[key] = (int) m.V.size() - 1;
		};
		std::vector<acd::Tri> f2;
		for (auto f : m.F) {
			int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
			f2.push_back({f[0], a, c});
			f2.push_back({f[1], b, a});
			f2.push_back({f[2], c, b});
			f2.push_back({a, b, c});
		}
		m.F = f2;
	}
	for (auto& v : m.V) v = v.normalized() * radius;
	return m;
}

TriMesh torus(double R, double r, int nu, int nv)
{
	TriMesh m;
	for (int i = 0; i < nu; ++i)
		for (int j = 0; j < nv; ++j) {
			double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
			m.V.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
			                 r * std::sin(v));
		}
	for (int i = 0; i < nu; ++i)
		for (int j = 0; j < nv; ++j) {
			int a = i * nv + j, b = ((i + 1) % nu) * nv + j, c = ((i + 1) % nu) * nv + (j + 1) % nv,
			    d = i * nv + (j + 1) % nv;
			m.F.push_back({a, b, c});
			m.F.push_back({a, c, d});
		}
	return m;
}

TriMesh lathe(const std::vector<Eigen::Vector2d>& profile, int nu)
{
	// poles at both ends, a ring of nu vertices for every profile point between them
	TriMesh    m;
	const int  rings = (int) profile.size() - 2;
	const auto ring  = [&](int k, int i) { return 1 + (k - 1) * nu + (i % nu); };
	m.V.emplace_back(0, 0, profile.front().y());
	for (int k = 1; k <= rings; ++k)
		for (int i = 0; i < nu; ++i) {
			const double u = 2 * M_PI * i / nu;
			m.V.emplace_back(profile[k].x() * std::cos(u), profile[k].x() * std::sin(u), profile[k].y());
		}
	m.V.emplace_back(0, 0, profile.back().y());
	const int top = (int) m.V.size() - 1;
	for (int i = 0; i < nu; ++i) {
		m.F.push_back({0, ring(1, i + 1), ring(1, i)});
		for (int k = 1; k < rings; ++k) {
			m.F.push_back({ring(k, i), ring(k, i + 1), ring(k + 1, i + 1)});
			m.F.push_back({ring(k, i), ring(k + 1, i + 1), ring(k + 1, i)});
		}
		m.F.push_back({ring(rings, i), ring(rings, i + 1), top});
	}
	return signed_volume(m) < 0 ? inverted(m) : m;
}

TriMesh merge(const TriMesh& a, const TriMesh& b)
{
	TriMesh m = a;
	append(m, b);
	return m;
}

TriMesh inverted(TriMesh m)
{
	for (auto& f : m.F) std::swap(f[1], f[2]);
	return m;
}

TriMesh subdivided(const TriMesh& m)
{
	TriMesh                            out = m;
	std::map<std::pair<int, int>, int> mid;
	const auto at = [&](int a, int b) {
		const auto key = std::minmax(a, b);
		auto       it  = mid.find(key);
		if (it != mid.end()) return it->second;
		out.V.push_back(0.5 * (m.V[a] + m.V[b]));
		return mid[key] = (int) out.V.size() - 1;
	};
	out.F.clear();
	for (const acd::Tri& t : m.F) {
		const int a = at(t[0], t[1]), b = at(t[1], t[2]), c = at(t[2], t[0]);
		out.F.insert(out.F.end(), {{t[0], a, c}, {a, t[1], b}, {c, b, t[2]}, {a, b, c}});
	}
	return out;
}

std::vector<Eigen::Vector2d> l_shape() { return {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}; }
std::vector<Eigen::Vector2d> u_shape()
{
	return {{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
}
std::vector<Eigen::Vector2d> slot_shape()
{
	return {{0, 0}, {3, 0}, {3, 2}, {1.6, 2}, {1.6, 0.4}, {1.4, 0.4}, {1.4, 2}, {0, 2}};
}
std::vector<Eigen::Vector2d> plus_shape()
{
	return {{1, 0}, {2, 0}, {2, 1}, {3, 1}, {3, 2}, {2, 2}, {2, 3}, {1, 3}, {1, 2}, {0, 2}, {0, 1}, {1, 1}};
}

acd::Plane plane(Vec3 n, double d)
{
	acd::Plane p;
	p.n = n.normalized();
	p.d = d;
	return p;
}

} // namespace shapes
