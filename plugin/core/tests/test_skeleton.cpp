#include "acd/structure/skeleton.h"
#include "acd/solid/solid.h"
#include "check.h"
#include "shapes.h"

using namespace acd;

namespace {

Skeleton of(const TriMesh& m, double tau)
{
	DecomposeOptions o;
	o.tau                 = tau;
	o.cut_plane_selection = CutPlaneSelection::MinSection;
	return skeleton(decompose(make_solid(m), o));
}

} // namespace

TEST_CASE("a bar's skeleton is one segment along its length")
{
	const Skeleton S = of(shapes::box(Vec3(0, 0, 0), Vec3(10, 1, 1)), 0.1);
	CHECK(S.components() == 1);
	REQUIRE(S.V.size() >= 2);
	double lo = 1e9, hi = -1e9;
	for (const Vec3& v : S.V) {
		lo = std::min(lo, v.x()), hi = std::max(hi, v.x());
		CHECK_NEAR(v.y(), 0.5, 1e-6);
		CHECK_NEAR(v.z(), 0.5, 1e-6);
	}
	CHECK(hi - lo > 8);
}

TEST_CASE("an L's skeleton joins its two arms in one component")
{
	const Skeleton S = of(shapes::extrude(shapes::l_shape(), 0, 0.5), 0.05);
	CHECK(S.pieces >= 2);
	CHECK(S.components() == 1);
	for (const Vec3& v : S.V) {   // inside the L's footprint
		CHECK(v.x() >= -1e-9);
		CHECK(v.y() >= -1e-9);
		CHECK((v.x() <= 1 + 1e-9 || v.y() <= 1 + 1e-9));
	}
}

TEST_CASE("a ring's skeleton closes its loop")
{
	const Skeleton S = of(shapes::torus(2, 0.4, 48, 12), 0.2);
	CHECK(S.components() == 1);
	CHECK(S.E.size() >= S.V.size());   // a cycle: as many edges as vertices, at least
	for (const Vec3& v : S.V) CHECK(std::abs(std::hypot(v.x(), v.y()) - 2) <= 0.4);
}
