#include "acd/prepare/winding_caps.h"
#include "acd/mesh/measures.h"
#include "shapes.h"
#include "check.h"

using namespace acd;

TEST_CASE("the winding caps of a box with an open top span the opening and hug the walls")
{
	// A 2 x 2 x 1 box without its top: the level set is the walls (moved onto them) and a lid across
	// the opening, near z = 1; the caps are the lid and its seam to the walls' rim, nothing of the walls
	// below it, and nothing reaches outside the box.
	const TriMesh box = shapes::box(Vec3(0, 0, 0), Vec3(2, 2, 1));
	TriMesh       open;
	open.V = box.V;
	for (const Tri& t : box.F)
		if ((box.V[t[0]] + box.V[t[1]] + box.V[t[2]]).z() < 2.9) open.F.push_back(t);
	CHECK(open.F.size() == box.F.size() - 2);
	const WindingNumber    wn(open);
	const NearestOnSurface near(open);
	const WindingCaps      caps = winding_caps(open, wn, near, 0.05);
	CHECK(caps.spacing == 0.05);
	CHECK(!caps.mesh.F.empty());
	double lid = 0, lid_area = 0;
	for (const Tri& t : caps.mesh.F) {
		const Vec3 a = caps.mesh.V[t[0]], b = caps.mesh.V[t[1]], c = caps.mesh.V[t[2]];
		for (const Vec3& p : {a, b, c}) {
			CHECK(p.minCoeff() > -0.05);
			CHECK((p - Vec3(2, 2, 1)).maxCoeff() < 0.05);
		}
		const Vec3 m = (a + b + c) / 3;
		CHECK(m.z() > 1 - 2 * caps.spacing);
		if (m.x() > 0.3 && m.x() < 1.7 && m.y() > 0.3 && m.y() < 1.7 && m.z() > 0.5) {
			lid      = std::max(lid, std::abs(m.z() - 1));
			lid_area += (b - a).cross(c - a).norm() / 2;
		}
	}
	CHECK(lid < 0.1);                  // the lid lies where the top was
	CHECK(lid_area > 0.9 * 1.4 * 1.4); // and covers the opening's middle
	// The lid is a sixth of the level set's area (4 of 2 x 2 + 4 x 2 + 4 x 2 + 4): not a shell.
	CHECK(caps.cap_share > 0.1);
	CHECK(caps.cap_share < 0.25);
	// A grid too fine for the budget grows coarser.
	CHECK(winding_caps(open, wn, near, 0.001, 100000).spacing > 0.02);
}
