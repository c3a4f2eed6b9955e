#include "acd/solid/separate.h"
#include "acd/mesh/measures.h"
#include "acd/solid/solid.h"
#include "check.h"
#include "shapes.h"

using namespace acd;

namespace {

using shapes::plane;

// Exactly two closed solids, each on its side of the plane, holding the input's volume together.
void check_split(const TriMesh& m, const Plane& pl, const Vec3& notch, double expect_first)
{
	SplitOutcome out;
	REQUIRE(separate(m, pl, notch, out));
	double total = 0;
	for (int s = 0; s < 2; ++s) {
		const Solid part = make_solid(out.parts[s]);   // closed, manifold and outward, or it throws
		CHECK(part.shells - part.cavities == 1);
		total += part.volume;
		for (const Vec3& v : out.parts[s].V) CHECK((s == 0 ? out.plane.eval(v) <= 1e-9 : out.plane.eval(v) >= -1e-9));
	}
	CHECK_NEAR(total, signed_volume(m), 1e-9 * std::abs(signed_volume(m)));
	// (a plane through vertices is nudged about 1e-7 of the size off them)
	if (expect_first > 0) CHECK_NEAR(signed_volume(out.parts[0]), expect_first, 1e-6);
	CHECK(out.cap_area > 0);
}

} // namespace

TEST_CASE("cut cases give exactly two closed parts")
{
	const TriMesh box = shapes::box(Vec3(0, 0, 0), Vec3(2, 1, 1));
	SUBCASE("a box across its middle") { check_split(box, plane(Vec3(1, 0, 0), 1), Vec3(1, 0, 0), 1.0); }
	SUBCASE("a box obliquely") { check_split(box, plane(Vec3(1, 0.3, 0.2), 1.1), Vec3(1, 0.5, 0.5), 0); }
	SUBCASE("an L prism through its notch")
	{
		check_split(shapes::extrude(shapes::l_shape(), 0, 1), plane(Vec3(1, 0, 0), 1), Vec3(1, 1, 0.5), 2.0);
	}
	SUBCASE("a box with a cavity, through the cavity")
	{
		const TriMesh hollow = shapes::merge(box, shapes::inverted(shapes::box(Vec3(0.5, 0.25, 0.25), Vec3(1.5, 0.75, 0.75))));
		check_split(hollow, plane(Vec3(1, 0, 0), 1), Vec3(1, 0.5, 0.5), 1.0 - 0.125);
	}
	SUBCASE("a ring through its axis: both cross-sections are cut")
	{
		const TriMesh ring = shapes::torus(2, 0.5, 48, 16);
		SplitOutcome  out;
		REQUIRE(separate(ring, plane(Vec3(1, 0, 0), 1e-3), Vec3(1e-3, 2, 0), out));
		CHECK(out.regions_cut == 2);
		check_split(ring, plane(Vec3(1, 0, 0), 1e-3), Vec3(1e-3, 2, 0), 0);
	}
}

TEST_CASE("only the cross-section at the notch is cut")
{
	// A U prism cut across both arms (y = 1.5): the arm nearer the notch falls off (its tip, 1 x 0.5 x 1),
	// the other arm is left whole.
	const TriMesh U = shapes::extrude(shapes::u_shape(), 0, 1);
	SplitOutcome  out;
	REQUIRE(separate(U, plane(Vec3(0, 1, 0), 1.5), Vec3(1, 1.5, 0.5), out));
	CHECK(out.regions_cut == 1);
	CHECK_NEAR(signed_volume(out.parts[1]), 0.5, 1e-9);
	CHECK_NEAR(signed_volume(out.parts[0]) + signed_volume(out.parts[1]), signed_volume(U), 1e-9);
	for (const Vec3& v : out.parts[1].V) CHECK(v.x() <= 1 + 1e-9);
}

TEST_CASE("a plane that misses the solid does not split it")
{
	SplitOutcome out;
	CHECK_FALSE(separate(shapes::box(Vec3(0, 0, 0), Vec3(1, 1, 1)), plane(Vec3(1, 0, 0), 5), Vec3(5, 0, 0), out));
}

TEST_CASE("a prong cut off whole keeps its side while the rest, reaching across, weighs on the same side")
{
	// A U prism with a short prong (x 0..1, up to y 3) and a tall one (x 2..3, up to y 10), cut at
	// y = 2 through the short prong's section: the prong's top comes off whole above the plane, and
	// the rest (the base below, the tall prong through the plane) has most of its vertices above too.
	const std::vector<Eigen::Vector2d> u = {{0, 0}, {3, 0}, {3, 10}, {2, 10}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
	const TriMesh m  = shapes::extrude(u, 0, 1);
	const Plane   pl = plane(Vec3(0, 1, 0), 2);
	SplitOutcome  out;
	REQUIRE(separate(m, pl, Vec3(0.5, 2, 0.5), out));
	CHECK(out.regions_cut == 1);
	for (const Vec3& v : out.parts[1].V) CHECK(out.plane.eval(v) >= -1e-9);   // the prong's top
	double below = 0, above = 0;
	for (const Vec3& v : out.parts[0].V) below = std::min(below, out.plane.eval(v)), above = std::max(above, out.plane.eval(v));
	CHECK(below < -1);   // the rest holds the base
	CHECK(above > 7);    // and the tall prong
	const Solid top = make_solid(out.parts[1]), rest = make_solid(out.parts[0]);
	CHECK(top.shells == 1);
	CHECK(rest.shells == 1);
	CHECK_NEAR(top.volume, 1.0, 1e-6);   // 1 x 1 x 1, the plane nudged at most 1e-6 of the size
	CHECK_NEAR(top.volume + rest.volume, signed_volume(m), 1e-9 * signed_volume(m));
	CHECK_NEAR(out.cap_area, 1.0, 1e-6);
}
