#include "acd/mesh/measures.h"
#include "check.h"
#include "shapes.h"

#include <Eigen/Geometry>

#include <cmath>

using namespace acd;

namespace {
// A prism over a regular n-gon of radius 1, from z = -1 to z = 1.
TriMesh prism(int n)
{
	TriMesh m;
	for (int i = 0; i < n; ++i) {
		const double u = 2 * M_PI * i / n;
		m.V.emplace_back(std::cos(u), std::sin(u), -1);
		m.V.emplace_back(std::cos(u), std::sin(u), 1);
	}
	for (int i = 0; i < n; ++i) {
		const int j = (i + 1) % n;
		m.F.push_back({2 * i, 2 * j, 2 * j + 1});
		m.F.push_back({2 * i, 2 * j + 1, 2 * i + 1});
	}
	for (int i = 1; i + 1 < n; ++i) {
		m.F.push_back({0, 2 * (i + 1), 2 * i});
		m.F.push_back({1, 2 * i + 1, 2 * (i + 1) + 1});
	}
	return m;
}
} // namespace

TEST_CASE("a line through a prism's edges crosses it exactly twice")
{
	// Each line runs from near the axis out through a vertical edge, where two side faces meet within
	// rounding of their borders (strict border tests lose or double such a crossing on some of them).
	for (int n = 5; n <= 40; ++n)
		for (int i = 0; i < n; ++i)
			for (double z : {0.0, 0.3}) {
				CAPTURE(n);
				CAPTURE(i);
				const double u = 2 * M_PI * i / n;
				const Vec3   a(std::cos(u), std::sin(u), 0), c = 0.1 * a + Vec3(0, 0, z);
				const std::vector<double> t = line_crossings(prism(n), c, a);
				REQUIRE(t.size() == 2);
				CHECK_NEAR(t[1], 0.9, 1e-12);   // the edge, at radius 1
				// the opposite side: a corner (even n) or the middle of a face (odd n)
				CHECK_NEAR(t[0], -0.1 - (n % 2 ? std::cos(M_PI / n) : 1.0), 1e-12);
			}
}

TEST_CASE("a line through a corner, or missing the mesh")
{
	const TriMesh m = prism(4);   // a square prism, corners at radius 1
	const Vec3    corner(1, 0, 1);
	const std::vector<double> t = line_crossings(m, Vec3::Zero(), corner.normalized());
	REQUIRE(t.size() == 2);
	CHECK_NEAR(t[1], corner.norm(), 1e-12);
	CHECK_NEAR(t[0], -corner.norm(), 1e-12);
	CHECK(line_crossings(m, Vec3(5, 5, 0), Vec3(0, 0, 1)).empty());
}

TEST_CASE("a pose frame's axis is the shape's own only where its spread stands apart")
{
	const Eigen::Matrix3d turn = Eigen::AngleAxisd(1.1, Vec3(2, 1, -1).normalized()).toRotationMatrix();
	for (const bool turned : {false, true}) {
		// The frame weighs faces at their centroids: a round plate of 48 sides has no preferred radius.
		TriMesh slab  = shapes::box(Vec3(0, 0, 0), Vec3(4, 2, 1));
		TriMesh plate = shapes::lathe({{0, 0}, {3, 0}, {3, 0.5}, {0, 0.5}}, 48);
		if (turned)
			for (TriMesh* m : {&slab, &plate})
				for (Vec3& v : m->V) v = turn * v;
		const PoseFrame a = pose_frame(slab), b = pose_frame(plate);
		CHECK((a.distinct(0) && a.distinct(1) && a.distinct(2)));
		CHECK((!b.distinct(0) && !b.distinct(1) && b.distinct(2)));   // a round plate: only its normal
		const Vec3 normal = turned ? Vec3(turn * Vec3::UnitZ()) : Vec3::UnitZ();
		CHECK(std::abs(Vec3(b.axes.row(2).transpose()).dot(normal)) == doctest::Approx(1.0).epsilon(1e-12));
		CHECK(a.spread[0] > a.spread[1]);
		CHECK(a.spread[1] > a.spread[2]);
	}
}
