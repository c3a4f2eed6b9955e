#include "acd/mesh/nearest.h"
#include "check.h"

using namespace acd;

namespace {

// The unit square at z = 0 with a square hole [0.25, 0.75]^2: an opening a cap would span.
TriMesh frame()
{
	TriMesh m;
	m.V = {Vec3(0, 0, 0),       Vec3(1, 0, 0),       Vec3(1, 1, 0),       Vec3(0, 1, 0),
	       Vec3(0.25, 0.25, 0), Vec3(0.75, 0.25, 0), Vec3(0.75, 0.75, 0), Vec3(0.25, 0.75, 0)};
	for (int k = 0; k < 4; ++k) {
		const int o = k, p = (k + 1) % 4, i = 4 + k, j = 4 + (k + 1) % 4;
		m.F.push_back(Tri{o, p, j});
		m.F.push_back(Tri{o, j, i});
	}
	return m;
}

} // namespace

TEST_CASE("distances to a surface: the nearest point, a point set's farthest, a surface's farthest")
{
	const NearestOnSurface near(frame());
	CHECK((near.closest(Vec3(0.1, 0.5, 2)) - Vec3(0.1, 0.5, 0)).norm() < 1e-12);
	CHECK(near.distance(Vec3(2, 0.5, 0)) == doctest::Approx(1));
	CHECK(near.distance(Vec3(0.5, 0.5, 0)) == doctest::Approx(0.25));   // the hole's middle
	CHECK(near.farthest({Vec3(0.1, 0.1, 0.1), Vec3(0.9, 0.9, -0.3)}) == doctest::Approx(0.3));

	// A cap over the hole, its corners on the frame: measured at its corners it would seem to lie on the
	// frame; its centroid, over the hole's middle, lies 0.25 from it.
	TriMesh cap;
	cap.V = {Vec3(0.5, 0.1, 0), Vec3(0.1, 0.9, 0), Vec3(0.9, 0.5, 0)};
	cap.F = {Tri{0, 2, 1}};
	CHECK(near.farthest(cap.V) < 1e-12);
	CHECK(near.farthest_on(cap) == doctest::Approx(0.25));
	// Raised, the cap's corners stand 0.1 off: the surface's farthest is its middle's, not a corner's.
	for (Vec3& v : cap.V) v.z() = 0.1;
	CHECK(near.farthest(cap.V) == doctest::Approx(0.1));
	CHECK(near.farthest_on(cap) == doctest::Approx(std::hypot(0.25, 0.1)));
	// An unused corner counts for a point set, not for a surface; an empty surface is at no distance.
	cap.V.push_back(Vec3(0, 0, 5));
	CHECK(near.farthest(cap.V) == doctest::Approx(5));
	CHECK(near.farthest_on(cap) == doctest::Approx(std::hypot(0.25, 0.1)));
	CHECK(near.farthest_on(TriMesh()) == 0);
}
