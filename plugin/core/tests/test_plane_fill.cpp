#include "acd/prepare/fill_holes.h"
#include "acd/prepare/plane_fill.h"
#include "shapes.h"
#include "check.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

using namespace acd;

namespace {

// The faces whose centroid lies within r of c removed.
TriMesh punched(const TriMesh& s, const Vec3& c, double r)
{
	TriMesh open;
	open.V = s.V;
	for (const Tri& t : s.F)
		if (((s.V[t[0]] + s.V[t[1]] + s.V[t[2]]) / 3 - c).norm() > r) open.F.push_back(t);
	return open;
}

// Volume by the divergence theorem over the faces, and the edges not used exactly twice.
double volume(const TriMesh& m)
{
	double v = 0;
	for (const Tri& t : m.F) v += m.V[t[0]].dot(m.V[t[1]].cross(m.V[t[2]])) / 6;
	return v;
}

int open_edges(const TriMesh& m)
{
	std::map<std::pair<int, int>, int> uses;
	for (const Tri& t : m.F)
		for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
	int n = 0;
	for (const auto& [e, c] : uses) n += c != 2;
	return n;
}

// Largest distance of a patch face's centroid and corners from the box's surface (in rotated frame R).
double off_box(const FilledHoles& f, const Eigen::Matrix3d& R, const Vec3& lo, const Vec3& hi)
{
	const auto off = [&](const Vec3& q) {
		const Vec3   p = R.transpose() * q;
		const double inside = std::min((p - lo).minCoeff(), (hi - p).minCoeff());
		const double outside = (p.cwiseMax(lo).cwiseMin(hi) - p).norm();
		return std::max(std::abs(inside), outside);
	};
	double worst = 0;
	for (size_t i = f.first_patch; i < f.mesh.F.size(); ++i) {
		const Tri& t = f.mesh.F[i];
		worst = std::max(worst, off((f.mesh.V[t[0]] + f.mesh.V[t[1]] + f.mesh.V[t[2]]) / 3));
		for (int v : t) worst = std::max(worst, off(f.mesh.V[v]));
	}
	return worst;
}

TriMesh turned(TriMesh m, const Eigen::Matrix3d& R)
{
	for (Vec3& p : m.V) p = R * p;
	return m;
}

} // namespace

TEST_CASE("holes across a box's corner, edge, a plate's rim and a slab's edge close on the box's own planes")
{
	const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())).toRotationMatrix();
	struct Case
	{
		Vec3   lo, hi, at;
		double r;
		int    corners;
	};
	const Case cases[] = {
	    {Vec3(0, 0, 0), Vec3(2, 2, 2), Vec3(2, 2, 2), 0.6, 1},       // three planes meet at the corner
	    {Vec3(0, 0, 0), Vec3(2, 2, 2), Vec3(2, 2, 1), 0.5, 0},       // two, along the edge
	    {Vec3(0, 0, 0), Vec3(4, 4, 0.5), Vec3(4, 2, 0.25), 0.7, 0},  // top, rim and bottom of a plate
	    {Vec3(0, 0, 0), Vec3(2, 0.5, 2), Vec3(2, 0.25, 2), 0.6, 2},  // a slab's short edge, both its corners
	};
	for (const Case& c : cases) {
		std::vector<std::vector<Tri>> patches;   // per pose
		for (const Eigen::Matrix3d& pose : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), R}) {
			const TriMesh box  = turned(shapes::subdivided(shapes::subdivided(shapes::subdivided(shapes::box(c.lo, c.hi)))), pose);
			const TriMesh open = punched(box, pose * c.at, c.r);
			REQUIRE(open_edges(open) > 0);
			const std::optional<FilledHoles> f = fill_holes(open);
			REQUIRE(f);
			patches.emplace_back(f->mesh.F.begin() + (long) f->first_patch, f->mesh.F.end());
			CHECK(f->holes == 1);
			CHECK(f->planar == 1);
			CHECK(f->faired == 0);
			CHECK(f->mesh.V.size() == open.V.size() + c.corners);
			CHECK(open_edges(f->mesh) == 0);
			// the box itself, not a faired or flat film across its edges
			CHECK(off_box(*f, pose, c.lo, c.hi) < 1e-9);
			CHECK(std::abs(volume(f->mesh) - volume(box)) < 1e-9 * volume(box));
		}
		// the same triangles in both poses: the grid's cocircular corners tie alike
		CHECK(patches[0] == patches[1]);
	}
}

TEST_CASE("a hole on a curved surface, or whose planes meet no corner near it, is no plane patch")
{
	const TriMesh s = shapes::sphere(4, 1.0);
	const TriMesh open = punched(s, Vec3(0, 0, 1), 0.4);
	const std::optional<FilledHoles> f = fill_holes(open);
	REQUIRE(f);
	CHECK(f->planar == 0);
	CHECK(f->faired == 1);
	// a box with one whole face missing: its rim runs on the four sides, none of which closes it
	const TriMesh box = shapes::subdivided(shapes::subdivided(shapes::box(Vec3(0, 0, 0), Vec3(1, 1, 1))));
	TriMesh       lid;
	lid.V = box.V;
	for (const Tri& t : box.F)
		if ((box.V[t[0]] + box.V[t[1]] + box.V[t[2]]).z() / 3 < 1 - 1e-9) lid.F.push_back(t);
	std::vector<RimEdge> rim;
	std::map<std::pair<int, int>, int> face_of;
	for (int i = 0; i < (int) lid.F.size(); ++i)
		for (int k = 0; k < 3; ++k) face_of[{lid.F[i][k], lid.F[i][(k + 1) % 3]}] = i;
	for (const auto& [e, i] : face_of)
		if (!face_of.count({e.second, e.first})) rim.push_back({e.first, e.second, i});
	REQUIRE(rim.size() == 16);
	CHECK(!plane_patch(lid, rim, 1e-9));
	const std::optional<FilledHoles> g = fill_holes(lid);   // the fairing closes it, flat
	REQUIRE(g);
	CHECK(g->planar == 0);
	CHECK(open_edges(g->mesh) == 0);
}

TEST_CASE("a rim that touches the crease it spans, and two openings that meet at a vertex, close on the box")
{
	const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())).toRotationMatrix();
	const Vec3 lo(0, 0, 0), hi(2, 2, 2);
	const TriMesh cube = shapes::subdivided(shapes::subdivided(shapes::subdivided(shapes::box(lo, hi))));   // edges 0.25
	const auto at_vertex = [&](const TriMesh& m, const Tri& t, const Vec3& p) {
		return std::any_of(t.begin(), t.end(), [&](int v) { return (m.V[v] - p).norm() < 1e-12; });
	};
	const auto centroid = [](const TriMesh& m, const Tri& t) { return Vec3((m.V[t[0]] + m.V[t[1]] + m.V[t[2]]) / 3); };
	// Across the edge x = z = 2, but a strip of the top's faces along y = 1 kept up to the edge, those
	// with no edge on it: the rim on the top runs out along the strip to the edge's vertex (2, 1, 2)
	// and back, so it touches the crease the patch spans.
	TriMesh touch;
	touch.V = cube.V;
	const Vec3 v(2, 1, 2);
	bool       reaches = false;
	for (const Tri& t : cube.F) {
		const Vec3 c     = centroid(cube, t);
		const bool inner = std::count_if(t.begin(), t.end(), [&](int w) { return cube.V[w].x() > 2 - 1e-9; }) <= 1;
		const bool strip = c.z() > 2 - 1e-9 && std::abs(c.y() - 1) < 0.2 && inner;
		reaches |= strip && at_vertex(cube, t, v);
		if ((c - v).norm() > 0.6 || strip) touch.F.push_back(t);
	}
	REQUIRE(reaches);
	// Two square openings in the top, 0.5 wide, that meet at the vertex (1, 1, 2).
	TriMesh pinch;
	pinch.V = cube.V;
	for (const Tri& t : cube.F) {
		const Vec3 c = centroid(cube, t);
		const bool a = c.x() > 0.5 && c.x() < 1 && c.y() > 0.5 && c.y() < 1, b = c.x() > 1 && c.x() < 1.5 && c.y() > 1 && c.y() < 1.5;
		if (c.z() < 2 - 1e-9 || !(a || b)) pinch.F.push_back(t);
	}
	for (const TriMesh* open : {&touch, &pinch}) {
		std::vector<std::vector<Tri>> patches;   // per pose
		for (const Eigen::Matrix3d& pose : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), R}) {
			const std::optional<FilledHoles> f = fill_holes(turned(*open, pose));
			REQUIRE(f);
			patches.emplace_back(f->mesh.F.begin() + (long) f->first_patch, f->mesh.F.end());
			CHECK(f->holes == 1);
			CHECK(f->planar == 1);
			CHECK(f->faired == 0);
			CHECK(f->mesh.V.size() == open->V.size());   // no corner: the planes meet along the box's edge
			CHECK(open_edges(f->mesh) == 0);
			CHECK(off_box(*f, pose, lo, hi) < 1e-9);
			CHECK(std::abs(volume(f->mesh) - volume(cube)) < 1e-9 * volume(cube));
		}
		CHECK(patches[0] == patches[1]);
	}
}
