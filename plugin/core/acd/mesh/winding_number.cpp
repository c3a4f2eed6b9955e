#include "acd/mesh/winding_number.h"
#include "acd/mesh/parallel.h"

#include <algorithm>
#include <numeric>

namespace acd {

namespace {

constexpr int    kLeaf = 8;     // faces per leaf, summed exactly
constexpr double kFar  = 3.0;   // a node is a dipole seen from farther than kFar times its radius

// The solid angle of triangle (a, b, c) seen from q, over 4 pi (Van Oosterom and Strackee).
double solid_angle(const std::array<Vec3, 3>& t, const Vec3& q)
{
	const Vec3   a = t[0] - q, b = t[1] - q, c = t[2] - q;
	const double la = a.norm(), lb = b.norm(), lc = c.norm();
	const double num = a.dot(b.cross(c));
	const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
	return num == 0 && den == 0 ? 0.0 : std::atan2(num, den) / (2 * M_PI);
}

} // namespace

WindingNumber::WindingNumber(const TriMesh& s)
{
	for (const Tri& t : s.F)
		if (finite_face(s, t)) tri.push_back({s.V[t[0]], s.V[t[1]], s.V[t[2]]});
	nodes.reserve(2 * tri.size() / kLeaf + 2);
	if (!tri.empty()) build(0, (int) tri.size());
}

// Median split along the widest extent of the faces' centroids (nth_element is deterministic: the
// tree depends only on the faces and their order).
int WindingNumber::build(int first, int count)
{
	const int id = (int) nodes.size();
	nodes.emplace_back();
	Node   n;
	double area = 0;
	n.first = first, n.count = count;
	Eigen::AlignedBox3d cbox;
	for (int i = first; i < first + count; ++i) {
		const auto& t = tri[i];
		const Vec3  v = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]);
		const Vec3  c = (t[0] + t[1] + t[2]) / 3;
		n.normal += v;
		n.centre += v.norm() * c;
		area += v.norm();
		for (const Vec3& p : t) n.box.extend(p);
		cbox.extend(c);
	}
	n.centre = area > 0 ? Vec3(n.centre / area) : n.box.center();
	for (int i = first; i < first + count; ++i)
		for (const Vec3& p : tri[i]) n.radius = std::max(n.radius, (p - n.centre).norm());
	if (count > kLeaf) {
		int axis;
		(cbox.max() - cbox.min()).maxCoeff(&axis);
		const auto key = [&](const std::array<Vec3, 3>& t) { return t[0][axis] + t[1][axis] + t[2][axis]; };
		const int half = count / 2;
		std::nth_element(tri.begin() + first, tri.begin() + first + half, tri.begin() + first + count,
		                 [&](const auto& a, const auto& b) { return key(a) < key(b); });
		n.left  = build(first, half);
		n.right = build(first + half, count - half);
	}
	nodes[id] = n;
	return id;
}

double WindingNumber::at(const Vec3& q) const
{
	if (nodes.empty()) return 0;
	double sum = 0;
	int    stack[128], top = 0;
	stack[top++] = 0;
	while (top > 0) {
		const Node& n = nodes[stack[--top]];
		const Vec3  d = n.centre - q;
		const double r = d.norm();
		if (r > kFar * n.radius && n.count > 1) sum += d.dot(n.normal) / (4 * M_PI * r * r * r);
		else if (n.left < 0)
			for (int i = n.first; i < n.first + n.count; ++i) sum += solid_angle(tri[i], q);
		else {
			stack[top++] = n.right;
			stack[top++] = n.left;
		}
	}
	return sum;
}

std::vector<double> WindingNumber::at(const std::vector<Vec3>& qs) const
{
	std::vector<double> w(qs.size());
	parallel_for_chunked(qs.size(), 256, [&](size_t i) { w[i] = at(qs[i]); });
	return w;
}

} // namespace acd
