#include "acd/decompose.h"
#include "shapes.h"
#include "check.h"

using namespace acd;

static Decomposition run(const TriMesh& m, double tau, CutPlaneSelection sel = CutPlaneSelection::Best)
{
	DecomposeOptions o;
	o.tau                 = tau;
	o.cut_plane_selection = sel;
	return decompose(make_solid(m), o);
}

static void check_partition(const TriMesh& input, const Decomposition& d)
{
	double vol = 0;
	for (int i : d.leaves()) {
		Solid s = make_solid(d.nodes[i].mesh);   // closed, manifold, outward: or it throws
		vol += s.volume;
	}
	const double v0 = signed_volume(input);
	CHECK_NEAR(vol / v0, 1.0, 1e-9);
}

TEST_CASE("convex gives one part")
{
	Decomposition d = run(shapes::sphere(2, 1.0), 0.01);
	CHECK(d.leaves().size() == 1);
}

TEST_CASE("l u plus known counts")
{
	for (auto sel : {CutPlaneSelection::Bisector, CutPlaneSelection::Best, CutPlaneSelection::MinSection}) {
		TriMesh L = shapes::extrude(shapes::l_shape(), 0, 0.5);
		auto    d = run(L, 0.01, sel);
		CHECK(d.leaves().size() == 2);
		check_partition(L, d);
		TriMesh U = shapes::extrude(shapes::u_shape(), 0, 1);
		d         = run(U, 0.01, sel);
		CHECK(d.leaves().size() == 3);
		check_partition(U, d);
		TriMesh P = shapes::extrude(shapes::plus_shape(), 0, 1);
		d         = run(P, 0.01, sel);
		CHECK((d.leaves().size() >= 4 && d.leaves().size() <= 5));
		check_partition(P, d);
		for (int i : d.leaves()) CHECK(d.nodes[i].concavity <= 0.01);
	}
}

TEST_CASE("torus needs at least three parts")
{
	TriMesh T = shapes::torus(2, 0.5, 48, 16);
	auto    d = run(T, 0.1);
	CHECK(d.leaves().size() >= 3);
	check_partition(T, d);
}

TEST_CASE("min section cuts the neck")
{
	// A spindle pinched by a lopsided V at z = 1.2: the bisector of the notch's faces leans with the V;
	// the narrowest cross-section through the notch is the horizontal disc.
	const TriMesh spindle = shapes::lathe({{0, 0}, {1, 0}, {1, 0.4}, {0.4, 1.2}, {1, 2.8}, {1, 3.2}, {0, 3.2}}, 48);
	const auto    neck    = run(spindle, 0.05, CutPlaneSelection::MinSection);
	const auto    bis     = run(spindle, 0.05, CutPlaneSelection::Bisector);
	CHECK((neck.nodes[0].has_plane && bis.nodes[0].has_plane));
	CHECK(std::abs(neck.nodes[0].plane.n.z()) > 0.999);
	CHECK(std::abs(bis.nodes[0].plane.n.z()) < 0.99);   // the test tells the two apart
	check_partition(spindle, neck);
	for (int i : neck.leaves()) CHECK(neck.nodes[i].concavity <= 0.05);
}
