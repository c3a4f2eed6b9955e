#include "acd/prepare/fill_holes.h"
#include "acd/mesh/measures.h"
#include "shapes.h"
#include "check.h"

#include <cmath>
#include <map>
#include <utility>

using namespace acd;

namespace {

// Edges used by exactly one face: 0 for a closed surface.
int border_edges(const TriMesh& m)
{
	std::map<std::pair<int, int>, int> uses;
	for (const Tri& t : m.F)
		for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
	int n = 0;
	for (const auto& [e, c] : uses) n += c == 1;
	return n;
}

TriMesh without_cap(const TriMesh& s, double z)
{
	TriMesh open;
	open.V = s.V;
	for (const Tri& t : s.F)
		if ((s.V[t[0]] + s.V[t[1]] + s.V[t[2]]).z() / 3 < z) open.F.push_back(t);
	return open;
}

} // namespace

TEST_CASE("a hole in a sphere is filled along the sphere, the rest kept")
{
	const TriMesh s    = shapes::sphere(4, 1.0);
	const TriMesh open = without_cap(s, 0.9);   // a hole about 0.87 across
	REQUIRE(border_edges(open) > 0);
	const std::optional<FilledHoles> f = fill_holes(open);
	REQUIRE(f);
	CHECK(f->holes == 1);
	CHECK(f->faired == 1);
	CHECK(border_edges(f->mesh) == 0);
	CHECK(f->mesh.F.size() > open.F.size());
	// the input's vertices kept where they were, in their order
	for (size_t i = 0; i < open.V.size(); ++i) CHECK((f->mesh.V[i] - open.V[i]).norm() == 0);
	// a flat film would lie the rim's sagitta (about 0.1) inside the sphere; the faired patch far nearer
	double off = 0;
	for (const Vec3& v : f->mesh.V) off = std::max(off, std::abs(v.norm() - 1));
	CHECK(off < 0.03);
	CHECK(std::abs(signed_volume(f->mesh) - signed_volume(s)) < 0.01 * signed_volume(s));
}

TEST_CASE("what the fill does not take: no hole, a non-manifold edge, too long a rim")
{
	const TriMesh s = shapes::sphere(3, 1.0);
	CHECK(!fill_holes(s));                     // closed: nothing to fill
	TriMesh fin = without_cap(s, 0.5);
	fin.V.push_back(Vec3(0, 0, 3));
	const Tri first = fin.F.front();
	fin.F.push_back({first[0], first[1], (int) fin.V.size() - 1});   // a third face on an edge
	CHECK(!fill_holes(fin));
	const TriMesh open = without_cap(s, 0.0);   // a hemisphere: a rim of many edges
	CHECK(fill_holes(open));
	CHECK(!fill_holes(open, 200, 8));
	CHECK(!fill_holes(without_cap(s, 0.5), 0));   // no hole allowed
}
