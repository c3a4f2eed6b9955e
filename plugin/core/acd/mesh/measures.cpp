#include "acd/mesh/measures.h"
#include "acd/mesh/disjoint_sets.h"
#include "acd/mesh/topology.h"

#include <Eigen/Eigenvalues>

#include <CGAL/Min_sphere_of_points_d_traits_3.h>
#include <CGAL/Min_sphere_of_spheres_d.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace acd {

double signed_volume(const TriMesh& m)
{
	// Relative to a vertex of the mesh: far from the origin the plain triple products cancel
	// catastrophically (a mesh 1e7 away would get a random sign).
	if (m.F.empty()) return 0;
	const Vec3 o = m.V[m.F[0][0]];
	double     v = 0;
	for (const Tri& t : m.F)
		v += (m.V[t[0]] - o).dot((m.V[t[1]] - o).cross(m.V[t[2]] - o));
	return v / 6.0;
}

double surface_area(const TriMesh& m)
{
	double a = 0;
	for (const Tri& t : m.F) a += (m.V[t[1]] - m.V[t[0]]).cross(m.V[t[2]] - m.V[t[0]]).norm();
	return a / 2;
}

void append(TriMesh& to, const TriMesh& from)
{
	const int o = (int) to.V.size();
	to.V.insert(to.V.end(), from.V.begin(), from.V.end());
	for (const Tri& t : from.F) to.F.push_back({t[0] + o, t[1] + o, t[2] + o});
}

Eigen::AlignedBox3d bounding_box(const std::vector<Vec3>& pts)
{
	Eigen::AlignedBox3d box;
	for (const Vec3& p : pts) box.extend(p);
	return box;
}

double bbox_diagonal(const std::vector<Vec3>& pts)
{
	return pts.empty() ? 0 : bounding_box(pts).diagonal().norm();
}

std::vector<Vec3> finite_vertices(const TriMesh& m)
{
	std::vector<Vec3> finite;
	for (const Vec3& v : m.V)
		if (v.allFinite()) finite.push_back(v);
	return finite;
}

Eigen::AlignedBox3d finite_box(const TriMesh& m)
{
	Eigen::AlignedBox3d box;
	for (const Vec3& v : m.V)
		if (v.allFinite()) box.extend(v);
	return box;
}

double extent(const std::vector<Vec3>& pts)
{
	if (pts.empty()) return 0;
	Vec3 c = Vec3::Zero();
	for (const Vec3& p : pts) c += p;
	c /= (double) pts.size();
	double r2 = 0;
	for (const Vec3& p : pts) r2 = std::max(r2, (p - c).squaredNorm());
	return 2 * std::sqrt(r2);
}

SurfaceMoments surface_moments(const TriMesh& m, const Vec3& o, const std::vector<int>* faces)
{
	SurfaceMoments mo;
	Vec3           sum = Vec3::Zero();
	const int      n   = faces ? (int) faces->size() : (int) m.F.size();
	for (int i = 0; i < n; ++i) {
		const Tri&   t = m.F[faces ? (*faces)[i] : i];
		const Vec3   a = m.V[t[0]] - o, b = m.V[t[1]] - o, d = m.V[t[2]] - o;
		const double w = 0.5 * (b - a).cross(d - a).norm();
		mo.area += w;
		sum += w * (a + b + d) / 3;
		mo.second += w / 12 * (a * a.transpose() + b * b.transpose() + d * d.transpose() + (a + b + d) * (a + b + d).transpose());
	}
	if (mo.area > 0) mo.centroid = o + sum / mo.area;
	return mo;
}

PoseFrame pose_frame(const TriMesh& m)
{
	// Area-weighted moments of the surface (triangle centroids): a property of the shape, not of
	// how densely or in which order its vertices are listed.
	PoseFrame   fr;
	double      area = 0;
	Vec3        c    = Vec3::Zero();
	std::vector<std::pair<double, Vec3>> w;
	w.reserve(m.F.size());
	for (const Tri& t : m.F) {
		const Vec3 &a = m.V[t[0]], &b = m.V[t[1]], &d = m.V[t[2]];
		const double ar = 0.5 * (b - a).cross(d - a).norm();
		w.emplace_back(ar, (a + b + d) / 3.0);
		area += ar;
		c += ar * w.back().second;
	}
	if (!(area > 0)) return fr;
	c /= area;
	Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
	for (const auto& [ar, p] : w) cov += ar * (p - c) * (p - c).transpose();
	Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov / area);
	Eigen::Matrix3d axes;   // rows, major axis first
	for (int i = 0; i < 3; ++i) axes.row(i) = es.eigenvectors().col(2 - i).transpose();
	Vec3 skew = Vec3::Zero();
	for (const auto& [ar, p] : w) skew += ar * (axes * (p - c)).array().cube().matrix();
	// Signs from the two most skewed axes; the least skewed one (a mirror symmetry's normal has
	// none) follows from handedness, which a rotation keeps.
	int weakest = 0;
	for (int i = 1; i < 3; ++i)
		if (std::abs(skew[i]) < std::abs(skew[weakest])) weakest = i;
	for (int i = 0; i < 3; ++i)
		if (i != weakest && skew[i] < 0) axes.row(i) *= -1;
	if (axes.determinant() < 0) axes.row(weakest) *= -1;
	fr.axes   = axes;
	for (int i = 0; i < 3; ++i) fr.spread[i] = es.eigenvalues()[2 - i];
	fr.tol    = 1e-9 * extent(m.V);
	return fr;
}

std::vector<int> face_components(const TriMesh& m, int* count)
{
	// Faces sharing an edge, in either direction, are joined: the faces on an edge are found in the
	// two endpoints' short edge lists, no hash map.
	const Topology   t(m);
	const int        nf = (int) m.F.size();
	DisjointSets     sets(nf);
	for (int f = 0; f < nf; ++f)
		for (int k = 0; k < 3; ++k) {
			const int a = m.F[f][k], b = m.F[f][(k + 1) % 3];
			for (int i = t.adj_start[b]; i < t.adj_start[b + 1]; ++i)   // b->a: the usual neighbour
				if (t.adj[i] == a) sets.unite(f, t.adj_corner[i] / 3);
			for (int i = t.adj_start[a]; i < t.adj_start[a + 1]; ++i)   // a->b again: misoriented or non-manifold
				if (t.adj[i] == b) sets.unite(f, t.adj_corner[i] / 3);
		}
	std::vector<int> comp(nf, -1), id(nf, -1);
	int              n = 0;
	for (int f = 0; f < nf; ++f) {
		int& r  = id[sets.root(f)];
		if (r < 0) r = n++;
		comp[f] = r;
	}
	if (count) *count = n;
	return comp;
}

namespace {
// Where the line c + t a meets triangle pqr (Moller-Trumbore), taking hits up to `border` (barycentric)
// beyond its edges; none when it misses or runs parallel.
std::optional<double> line_meets(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& c, const Vec3& a, double border)
{
	const Vec3   e1 = q - p, e2 = r - p, h = a.cross(e2);
	const double det = e1.dot(h);
	if (std::abs(det) < 1e-300) return std::nullopt;
	const Vec3   s = c - p;
	const double u = s.dot(h) / det;
	if (u < -border || u > 1 + border) return std::nullopt;
	const Vec3   qv = s.cross(e1);
	const double v  = a.dot(qv) / det;
	if (v < -border || u + v > 1 + border) return std::nullopt;
	return e2.dot(qv) / det;
}
} // namespace

bool inside(const TriMesh& m, const Vec3& p)
{
	// A direction unlikely to graze edges of axis-aligned or symmetric meshes.
	const Vec3 dir = Vec3(0.5773502691896258, 0.5773502691896257, 0.5773502691896259).normalized() +
	                 Vec3(1e-3, -2e-3, 3e-3);
	int hits = 0;
	for (const Tri& t : m.F) {
		const std::optional<double> at = line_meets(m.V[t[0]], m.V[t[1]], m.V[t[2]], p, dir, 0);
		if (at && *at > 0) ++hits;
	}
	return hits % 2 == 1;
}

std::vector<double> line_crossings(const TriMesh& m, const Vec3& c, const Vec3& a)
{
	std::vector<double> ts;
	for (const Tri& t : m.F)
		if (const std::optional<double> at = line_meets(m.V[t[0]], m.V[t[1]], m.V[t[2]], c, a, 1e-9)) ts.push_back(*at);
	std::sort(ts.begin(), ts.end());
	const double        merge = 1e-9 * bbox_diagonal(m.V);
	std::vector<double> out;
	for (double t : ts)
		if (out.empty() || t - out.back() > merge) out.push_back(t);
	return out;
}

double enclosing_diameter(const std::vector<Vec3>& pts)
{
	using K      = CGAL::Simple_cartesian<double>;
	using Traits = CGAL::Min_sphere_of_points_d_traits_3<K, double>;
	std::vector<K::Point_3> p;
	p.reserve(pts.size());
	for (const Vec3& v : pts) p.emplace_back(v.x(), v.y(), v.z());
	CGAL::Min_sphere_of_spheres_d<Traits> ms(p.begin(), p.end());
	return 2 * ms.radius();
}

} // namespace acd
