#include "acd/mesh/orient.h"
#include "acd/mesh/measures.h"
#include "shapes.h"
#include "check.h"

using namespace acd;

TEST_CASE("patches turned against their neighbours turn back, pieces keep their own orientation")
{
	const TriMesh s = shapes::sphere(3, 1.0);
	TriMesh       m = shapes::merge(s, shapes::inverted(shapes::box(Vec3(3, 0, 0), Vec3(4, 1, 1))));
	int           patch = 0;
	for (size_t f = 0; f < s.F.size(); ++f)   // a cap of the sphere, a fifth of it, turned
		if ((s.V[s.F[f][0]] + s.V[s.F[f][1]] + s.V[s.F[f][2]]).z() > 1.8) std::swap(m.F[f][1], m.F[f][2]), ++patch;
	CHECK(patch > 0);
	CHECK(orient_patches(m) == patch);
	CHECK_NEAR(signed_volume(m), signed_volume(s) - 1.0, 1e-9);   // the sphere outward, the box still inward
	CHECK(m.F.size() == s.F.size() + 12);
	CHECK(orient_patches(m) == 0);
}
