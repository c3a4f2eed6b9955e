#include "acd/prepare/alpha_wrap.h"
#include "acd/prepare/wrap_solid.h"
#include "acd/mesh/measures.h"
#include "acd/solid/solid.h"
#include "acd/mesh/weld.h"
#include "shapes.h"
#include "check.h"

#include <cmath>

using namespace acd;

TEST_CASE("winding number is one inside zero outside and signed by orientation")
{
	const TriMesh             s = shapes::sphere(3, 1.0);
	const std::vector<Vec3>   p = {Vec3(0, 0, 0), Vec3(0.5, -0.3, 0.2), Vec3(3, 0, 0), Vec3(0, 1.5, 0)};
	const std::vector<double> w = winding_numbers(s, p);
	CHECK_NEAR(w[0], 1.0, 1e-9);
	CHECK_NEAR(w[1], 1.0, 1e-9);
	CHECK_NEAR(w[2], 0.0, 1e-9);
	CHECK_NEAR(w[3], 0.0, 1e-9);
	CHECK_NEAR(winding_numbers(shapes::inverted(s), p)[0], -1.0, 1e-9);
}

TEST_CASE("a valid solid is returned as given")
{
	const TriMesh         b = shapes::box(Vec3(0, 0, 0), Vec3(2, 1, 1));
	const WrapSolidResult r = wrap_solid(b, 0.05, 0.005, 0.4);
	CHECK(!r.wrapped);
	CHECK(r.tries == 0);
	CHECK(r.mesh.F.size() == b.F.size());
}

TEST_CASE("a sphere with a small hole is wrapped solid not as a skin")
{
	// Faces around the north pole removed: a hole about 0.28 across in a sphere of diameter 2. A wrap
	// with alpha 0.05 slips through it and hugs both sides of the surface; a coarser wrap closes it.
	TriMesh s = shapes::sphere(3, 1.0), open;
	open.V = s.V;
	for (const Tri& t : s.F)
		if ((s.V[t[0]] + s.V[t[1]] + s.V[t[2]]).z() / 3 < 0.99) open.F.push_back(t);
	CHECK(open.F.size() < s.F.size());
	const double skin = signed_volume(alpha_wrap(open, 0.05, 0.005));
	const double ball = 4.0 / 3.0 * M_PI;
	CHECK(skin < 0.2 * ball);

	const WrapSolidResult r = wrap_solid(open, 0.05, 0.005, 0.4);
	CHECK(r.wrapped);
	CHECK(r.tries >= 2);
	CHECK(r.alpha > 0.05);
	CHECK(r.inside >= 0.5);
	CHECK(!r.reason.empty());
	CHECK(signed_volume(r.mesh) > 0.8 * ball);
	CHECK(make_solid(r.mesh).mesh.F.size() == r.mesh.F.size());
}

TEST_CASE("an open shell no wrap fills keeps its skin")
{
	// A hemisphere encloses nothing: no alpha recovers an interior, and the first wrap (the skin, a
	// thin closed sheet about the surface) is kept rather than a coarse blob.
	TriMesh s = shapes::sphere(3, 1.0), cup;
	cup.V = s.V;
	for (const Tri& t : s.F)
		if ((s.V[t[0]] + s.V[t[1]] + s.V[t[2]]).z() < 0) cup.F.push_back(t);
	const WrapSolidResult r = wrap_solid(cup, 0.05, 0.005, 0.4);
	CHECK(r.wrapped);
	CHECK(r.alpha == 0.05);
	CHECK(signed_volume(r.mesh) < 0.1 * (2.0 / 3.0 * M_PI));
}

TEST_CASE("a triangle soup of a closed box is welded not wrapped")
{
	// As an STL stores it: every face with its own three corners, one corner off by 1e-9.
	const TriMesh b = shapes::box(Vec3(0, 0, 0), Vec3(2, 1, 1));
	TriMesh       soup;
	for (const Tri& t : b.F) {
		const int n = (int) soup.V.size();
		for (int v : t) soup.V.push_back(b.V[v]);
		soup.F.push_back({n, n + 1, n + 2});
	}
	soup.V[0] += Vec3(1e-9, 0, 0);
	const WrapSolidResult r = wrap_solid(soup, 0.05, 0.005, 0.4);
	CHECK(!r.wrapped);
	CHECK(r.welded == (int) soup.V.size() - (int) b.V.size());
	CHECK(r.mesh.F.size() == b.F.size());
	CHECK_NEAR(signed_volume(r.mesh), 2.0, 1e-8);
	int merged = -1;
	CHECK((weld(b, 1e-6, &merged).F.size() == b.F.size() && merged == 0));
}
