#include "acd/mesh/decimate.h"
#include "acd/mesh/parallel.h"
#include "acd/solid/solid.h"
#include "check.h"
#include "shapes.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

using namespace acd;

namespace {

// Measured here, not by the core: the distance from p to the torus (R, r) around z, and a mesh's
// volume and Euler characteristic.
double torus_distance(const Vec3& p, double R, double r)
{
	return std::abs(std::hypot(std::hypot(p.x(), p.y()) - R, p.z()) - r);
}

double volume(const TriMesh& m)
{
	double v = 0;
	for (const Tri& t : m.F) v += m.V[t[0]].dot(m.V[t[1]].cross(m.V[t[2]])) / 6;
	return v;
}

long euler(const TriMesh& m)
{
	std::set<std::pair<int, int>> edges;
	std::set<int>                 verts;
	for (const Tri& t : m.F)
		for (int k = 0; k < 3; ++k) {
			edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
			verts.insert(t[k]);
		}
	return (long) verts.size() - (long) edges.size() + (long) m.F.size();
}

} // namespace

TEST_CASE("decimate: a fine torus to a twentieth of its faces stays a closed torus near the surface")
{
	const double  R = 1, r = 0.4;
	const TriMesh fine = shapes::torus(R, r, 200, 100);
	const double  bar  = 0.01;
	const Decimated d  = decimate(fine, (int) fine.F.size() / 20, bar);
	CHECK(d.mesh.F.size() <= fine.F.size() / 20);
	CHECK(d.mesh.F.size() >= fine.F.size() / 20 - 2);
	const Solid s = make_solid(d.mesh);   // closed, edge-manifold, oriented: or it throws
	CHECK(s.shells == 1);
	CHECK(s.self_intersections == 0);
	CHECK(euler(d.mesh) == 0);   // still genus one
	double far = 0;
	for (const Vec3& p : d.mesh.V) far = std::max(far, torus_distance(p, R, r));
	CHECK(far <= 2 * bar);
	CHECK_NEAR(volume(d.mesh) / (2 * M_PI * M_PI * R * r * r), 1.0, 0.02);
	// The same input, the same output, on one thread too: each block of collapses is judged ahead on
	// every core, and a judgement a collapse before it made stale is judged again in turn.
	for (int threads : {0, 1}) {
		const ThreadLimit limit(threads);
		const Decimated   again = decimate(fine, (int) fine.F.size() / 20, bar);
		CHECK(again.mesh.V == d.mesh.V);
		CHECK(again.mesh.F == d.mesh.F);
	}
}

TEST_CASE("decimate: a flat-sided solid keeps its shape exactly; a tiny error bar keeps every face")
{
	// A box whose sides are finely triangulated (midpoints, four times): collapses on the flat sides
	// cost nothing, so the box comes back with the same volume, every vertex on a side.
	TriMesh box = shapes::box({0, 0, 0}, {1, 1, 1});
	for (int k = 0; k < 4; ++k) box = shapes::subdivided(box);
	const Decimated d   = decimate(box, 12, 1e-6);
	CHECK(d.mesh.F.size() < box.F.size() / 4);
	CHECK_NEAR(volume(d.mesh), 1.0, 1e-9);
	for (const Vec3& p : d.mesh.V)
		CHECK(std::min({p.x(), 1 - p.x(), p.y(), 1 - p.y(), p.z(), 1 - p.z()}) <= 1e-9);   // on a side
	make_solid(d.mesh);
	// A curved surface under an error bar far below its facets' sag: nothing collapses.
	const TriMesh sphere = shapes::sphere(3, 1);
	CHECK(decimate(sphere, 10, 1e-9).mesh.F.size() == sphere.F.size());
}

TEST_CASE("decimate: the same surface in another order of its vertices and faces gives the same copy")
{
	const TriMesh fine = shapes::torus(1, 0.4, 120, 60);
	const Decimated d  = decimate(fine, (int) fine.F.size() / 10, 0.01);
	// Vertices shuffled (a fixed permutation), faces reversed and each started at another corner.
	std::vector<int> perm(fine.V.size());
	for (size_t i = 0; i < perm.size(); ++i) perm[i] = (int) ((i * 7919) % perm.size());
	REQUIRE(std::set<int>(perm.begin(), perm.end()).size() == perm.size());
	TriMesh shuffled;
	shuffled.V.resize(fine.V.size());
	for (size_t i = 0; i < perm.size(); ++i) shuffled.V[perm[i]] = fine.V[i];
	for (size_t f = fine.F.size(); f-- > 0;) {
		const Tri& t = fine.F[f];
		shuffled.F.push_back({perm[t[(f + 1) % 3]], perm[t[(f + 2) % 3]], perm[t[f % 3]]});
	}
	const Decimated again = decimate(shuffled, (int) fine.F.size() / 10, 0.01);
	CHECK(again.mesh.V == d.mesh.V);
	CHECK(again.mesh.F == d.mesh.F);
}

TEST_CASE("decimate: the same surface in another pose gives the same copy, turned with it")
{
	// A torus bent and stretched so that its principal axes are its own (no two equal spreads).
	TriMesh fine = shapes::torus(1, 0.4, 120, 60);
	for (Vec3& p : fine.V) p = Vec3(1.4 * p.x(), p.y(), 0.7 * p.z() + 0.15 * p.x() * p.x() + 0.1 * p.y());
	const Decimated d = decimate(fine, (int) fine.F.size() / 10, 0.01);
	REQUIRE(d.mesh.F.size() <= fine.F.size() / 10);
	int same = 0;
	for (int k = 0; k < 5; ++k) {
		const Eigen::Matrix3d R =
		    Eigen::AngleAxisd(0.7 + k, Vec3(1, 2 - k, 0.5 * k).normalized()).toRotationMatrix();
		TriMesh turned = fine;
		for (Vec3& p : turned.V) p = R * p + Vec3(3, -2, 1);
		const Decimated again = decimate(turned, (int) fine.F.size() / 10, 0.01);
		if (again.mesh.F != d.mesh.F || again.mesh.V.size() != d.mesh.V.size()) continue;
		double apart = 0;
		for (size_t i = 0; i < d.mesh.V.size(); ++i)
			apart = std::max(apart, (R.transpose() * (again.mesh.V[i] - Vec3(3, -2, 1)) - d.mesh.V[i]).norm());
		same += apart < 1e-9;
	}
	CHECK(same == 5);
}
