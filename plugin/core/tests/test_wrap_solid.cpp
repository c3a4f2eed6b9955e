#include "acd/prepare/alpha_wrap.h"
#include "acd/prepare/wrap_solid.h"
#include "acd/mesh/measures.h"
#include "acd/solid/solid.h"
#include "acd/mesh/weld.h"
#include "shapes.h"
#include "check.h"

#include <cmath>
#include <map>
#include <set>

using namespace acd;

TEST_CASE("winding number is one inside zero outside and signed by orientation")
{
	// The fast evaluation counts far faces as dipoles: a few percent off, far less than the 1/2 it is cut at.
	const TriMesh             s = shapes::sphere(3, 1.0);
	const std::vector<Vec3>   p = {Vec3(0, 0, 0), Vec3(0.5, -0.3, 0.2), Vec3(3, 0, 0), Vec3(0, 1.5, 0)};
	const std::vector<double> w = winding_numbers(s, p);
	CHECK_NEAR(w[0], 1.0, 0.04);
	CHECK_NEAR(w[1], 1.0, 0.04);
	CHECK_NEAR(w[2], 0.0, 0.04);
	CHECK_NEAR(w[3], 0.0, 0.04);
	CHECK_NEAR(winding_numbers(shapes::inverted(s), p)[0], -1.0, 0.04);
}

TEST_CASE("a valid solid is returned as given")
{
	const TriMesh         b = shapes::box(Vec3(0, 0, 0), Vec3(2, 1, 1));
	const WrapSolidResult r = wrap_solid(b, 0.05, 0.005, 0.4);
	CHECK(!r.wrapped);
	CHECK(r.tries == 0);
	CHECK(r.mesh.F.size() == b.F.size());
}

namespace {

// The sphere without the faces whose centroid lies within `radius` of any of `at` (unit directions).
TriMesh punched(const TriMesh& s, const std::vector<Vec3>& at, double radius)
{
	TriMesh open;
	open.V = s.V;
	for (const Tri& t : s.F) {
		const Vec3 c    = (s.V[t[0]] + s.V[t[1]] + s.V[t[2]]) / 3;
		bool       keep = true;
		for (const Vec3& a : at) keep = keep && (c - a.normalized()).norm() > radius;
		if (keep) open.F.push_back(t);
	}
	return open;
}

// Largest distance from the mesh's vertices to the unit sphere's surface.
double off_unit_sphere(const TriMesh& m)
{
	double d = 0;
	for (const Vec3& v : m.V) d = std::max(d, std::abs(v.norm() - 1));
	return d;
}

// The wrap of a punched unit sphere: a solid, not a skin (nearly the ball's volume), nothing outside
// the sphere but the wrap's offset, and the caps' depth inside it no more than the reported distance.
void check_capped(const WrapSolidResult& r, double ball)
{
	CHECK(r.capped);
	CHECK(!r.skin);
	CHECK(std::abs(signed_volume(r.mesh)) > 0.9 * ball);
	double out = 0, in = 0;
	for (const Vec3& v : r.mesh.V) out = std::max(out, v.norm() - 1), in = std::max(in, 1 - v.norm());
	CHECK(out < 0.015);
	CHECK(r.to_input >= in - 0.005);   // the faceted sphere lies within 0.005 of the round one
}

} // namespace

TEST_CASE("a sphere with holes is wrapped solid along its own surface, not as a skin")
{
	// Faces around the north pole removed: a hole about 0.28 across in a sphere of diameter 2. A wrap
	// with alpha 0.05 slips through it and hugs both sides of the surface; the winding number's caps
	// close it where the sphere would be, at the same alpha.
	const TriMesh s    = shapes::sphere(4, 1.0);
	const double  ball = std::abs(signed_volume(s));
	const TriMesh open = punched(s, {Vec3(0, 0, 1)}, 0.14);
	CHECK(open.F.size() < s.F.size());
	CHECK(signed_volume(alpha_wrap(open, 0.05, 0.005)) < 0.2 * ball);

	const WrapSolidResult r = wrap_solid(open, 0.05, 0.005, 0.4, 0.5, 0.25, /*fill=*/false);
	CHECK(r.wrapped);
	CHECK(r.capped);
	CHECK(!r.skin);
	CHECK(r.tries == 1);   // its cap lies farther than alpha from the rim: wrapped with it at once
	CHECK(r.alpha == 0.05);
	CHECK(r.inside >= 0.95);
	CHECK(!r.reason.empty());
	CHECK(std::abs(signed_volume(r.mesh)) > 0.97 * ball);
	CHECK(off_unit_sphere(r.mesh) < 0.03);
	CHECK(make_solid(r.mesh).mesh.F.size() == r.mesh.F.size());
	// The reported distances, re-measured: the wrap's vertices from the open sphere's faces (no closer
	// than from the whole sphere) and the open sphere's vertices from the wrap's surface.
	CHECK(r.to_input >= off_unit_sphere(r.mesh) - 0.005);   // the faceted sphere lies within 0.005 of it
	CHECK(r.to_input < 0.2);   // a cap's middle from the rim: about the hole's radius
	CHECK(r.from_input < 0.02);
}

namespace {

const std::vector<Vec3> kHoleDirs = {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(-1, 1, 0), Vec3(0, 1, -1),
                                     Vec3(1, 1, 1), Vec3(-1, -1, -1), Vec3(1, -1, 0.3), Vec3(-1, 0.2, -1), Vec3(0.3, 1, 1)};

// The unit sphere with `holes` holes, hole k of radius 0.1 + 0.25 k / holes; `sag` the largest rim's sagitta.
TriMesh holed_sphere(int holes, double& sag)
{
	TriMesh open = shapes::sphere(4, 1.0);
	sag          = 0;
	for (int k = 0; k < holes; ++k) {
		const double radius = 0.1 + 0.25 * k / holes;
		open = punched(open, {kHoleDirs[k]}, radius);
		sag  = std::max(sag, 1 - std::sqrt(1 - radius * radius));
	}
	return open;
}

// Loops of border edges (edges of one face), counted as the border's connected pieces.
int border_loops(const TriMesh& m)
{
	std::map<std::pair<int, int>, int> uses;
	for (const Tri& t : m.F)
		for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
	std::vector<int> root(m.V.size());
	for (size_t i = 0; i < root.size(); ++i) root[i] = (int) i;
	const auto find = [&](int v) { while (root[v] != v) v = root[v] = root[root[v]]; return v; };
	std::set<int> on_border;
	for (const auto& [e, c] : uses)
		if (c == 1) root[find(e.first)] = find(e.second), on_border.insert(e.first), on_border.insert(e.second);
	std::set<int> loops;
	for (int v : on_border) loops.insert(find(v));
	return (int) loops.size();
}

} // namespace

TEST_CASE("holes in a sphere are filled and faired along it, the rest kept as it is")
{
	// The fill continues the sphere's curvature: its patches lie far nearer the sphere than the flat caps
	// (about the sagitta inside it), and the input's own faces are the solid's.
	const double ball = std::abs(signed_volume(shapes::sphere(4, 1.0)));
	for (int holes : {1, 3, 10}) {
		CAPTURE(holes);
		double                sag  = 0;
		const TriMesh         open = holed_sphere(holes, sag);
		const WrapSolidResult r    = wrap_solid(open, 0.05, 0.005, 0.4);
		CHECK(!r.wrapped);
		CHECK(r.filled == border_loops(open));   // two of ten holes overlap: nine loops
		CHECK(r.filled >= holes - 1);
		CHECK(!r.capped);
		REQUIRE(r.solid);
		CHECK(r.solid->self_intersections == 0);
		CHECK(std::abs(signed_volume(r.mesh)) > 0.97 * ball);
		CHECK(off_unit_sphere(r.mesh) < 0.35 * sag);
		CHECK(r.to_input >= off_unit_sphere(r.mesh) - 0.005);   // the reported reach, re-measured
		CHECK(r.from_input < 1e-9);                               // every input vertex is on the solid
	}
}

TEST_CASE("one, three and ten holes of growing size close along the sphere")
{
	const TriMesh s    = shapes::sphere(4, 1.0);
	const double  ball = std::abs(signed_volume(s));
	const std::vector<Vec3> dirs = {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(-1, 1, 0), Vec3(0, 1, -1),
	                                Vec3(1, 1, 1), Vec3(-1, -1, -1), Vec3(1, -1, 0.3), Vec3(-1, 0.2, -1), Vec3(0.3, 1, 1)};
	for (int holes : {1, 3, 10}) {
		// Hole k of n has radius 0.1 + 0.25 k / n: every cap within max_alpha (0.4) of the rim.
		TriMesh open = s;
		double  sag  = 0;   // of the largest hole's rim
		for (int k = 0; k < holes; ++k) {
			const double radius = 0.1 + 0.25 * k / holes;
			open = punched(open, {dirs[k]}, radius);
			sag  = std::max(sag, 1 - std::sqrt(1 - radius * radius));
		}
		CAPTURE(holes);
		const WrapSolidResult r = wrap_solid(open, 0.05, 0.005, 0.4, 0.5, 0.25, /*fill=*/false);
		check_capped(r, ball);
		// A cap spans its rim like a soap film, nearly flat: about the rim's sagitta inside the sphere.
		CHECK(off_unit_sphere(r.mesh) > 0.5 * sag);
	}
}

TEST_CASE("two holed spheres that cross each other are wrapped, not filled")
{
	// Each fills to a closed sphere, but together they cross: no solid, so the caps' wrap takes over.
	double  sag = 0;
	TriMesh two = holed_sphere(1, sag);
	TriMesh b   = two;
	for (Vec3& v : b.V) v += Vec3(0.8, 0.1, 0.05);
	append(two, b);
	const WrapSolidResult r = wrap_solid(two, 0.05, 0.005, 0.4);
	CHECK(r.wrapped);
	CHECK(r.filled == 0);
	CHECK(!r.skin);
}

TEST_CASE("a flipped patch and a triangle soup still enclose their solid")
{
	const TriMesh s    = shapes::sphere(4, 1.0);
	const double  ball = std::abs(signed_volume(s));
	TriMesh       flipped = punched(s, {Vec3(0, 0, 1)}, 0.14);
	for (Tri& t : flipped.F)
		if ((s.V[t[0]] + s.V[t[1]] + s.V[t[2]]).x() > 2.4) std::swap(t[1], t[2]);   // a tenth of the area
	TriMesh soup;   // every face its own corners: what an STL stores
	for (const Tri& t : punched(s, {Vec3(0, 0, 1), Vec3(1, 0, 0)}, 0.3).F) {
		const int n = (int) soup.V.size();
		for (int v : t) soup.V.push_back(s.V[v]);
		soup.F.push_back({n, n + 1, n + 2});
	}
	for (const TriMesh* m : {&flipped, &soup}) {
		check_capped(wrap_solid(*m, 0.05, 0.005, 0.4, 0.5, 0.25, /*fill=*/false), ball);
		const WrapSolidResult r = wrap_solid(*m, 0.05, 0.005, 0.4);   // by default their holes are filled
		CHECK(!r.wrapped);
		CHECK(r.filled == (m == &flipped ? 1 : 2));
		CHECK(std::abs(std::abs(signed_volume(r.mesh)) - ball) < 0.02 * ball);
	}
}

TEST_CASE("a flat sheet is wrapped as a skin")
{
	TriMesh sheet;
	const int n = 20;
	for (int j = 0; j <= n; ++j)
		for (int i = 0; i <= n; ++i) sheet.V.emplace_back(double(i) / n, double(j) / n, 0.01 * std::sin(6.0 * i / n));
	for (int j = 0; j < n; ++j)
		for (int i = 0; i < n; ++i) {
			const int a = j * (n + 1) + i;
			sheet.F.push_back({a, a + 1, a + n + 2});
			sheet.F.push_back({a, a + n + 2, a + n + 1});
		}
	const WrapSolidResult r = wrap_solid(sheet, 0.05, 0.005, 0.4);
	CHECK(r.wrapped);
	CHECK(r.skin);
	CHECK(!r.capped);
	CHECK(r.tries == 1);
	CHECK(std::abs(signed_volume(r.mesh)) < 0.05);
	CHECK(r.to_input < 0.02);
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
	CHECK(r.skin);
	CHECK(!r.capped);
	CHECK(r.cap_share > 0.25);
	CHECK(r.filled == 0);
	CHECK(r.alpha == 0.05);
	CHECK(signed_volume(r.mesh) < 0.1 * (2.0 / 3.0 * M_PI));
}

TEST_CASE("an opening wider than the coarsest wrap would close keeps the skin")
{
	// A sphere with a hole 1.6 across: a helmet rather than a ball with a hole. Its cap would lie about
	// 0.8 from the rim, beyond max_alpha (0.4), though it spans less than a quarter of the level set.
	const WrapSolidResult r = wrap_solid(punched(shapes::sphere(4, 1.0), {Vec3(0, 0, 1)}, 0.8), 0.05, 0.005, 0.4);
	CHECK(r.wrapped);
	CHECK(r.skin);
	CHECK(!r.capped);
	CHECK(r.cap_share < 0.25);
	CHECK(r.filled == 0);
	CHECK(r.alpha == 0.05);
	// The skin hugs the sheet: its corners at the offset, the faces that curl round the rim within alpha.
	CHECK(r.to_input < 0.05);
	CHECK(r.to_input > 0.005);
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
