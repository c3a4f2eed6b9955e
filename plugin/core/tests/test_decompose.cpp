#include "acd/decompose.h"
#include "shapes.h"
#include "testing.h"

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

ACD_TEST(convex_gives_one_part)
{
	Decomposition d = run(shapes::sphere(2, 1.0), 0.01);
	CHECK(d.leaves().size() == 1);
}

ACD_TEST(l_u_plus_known_counts)
{
	for (auto sel : {CutPlaneSelection::Bisector, CutPlaneSelection::Best}) {
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
		CHECK(d.leaves().size() >= 4 && d.leaves().size() <= 5);
		check_partition(P, d);
		for (int i : d.leaves()) CHECK(d.nodes[i].concavity <= 0.01);
	}
}

ACD_TEST(torus_needs_at_least_three_parts)
{
	TriMesh T = shapes::torus(2, 0.5, 48, 16);
	auto    d = run(T, 0.1);
	CHECK(d.leaves().size() >= 3);
	check_partition(T, d);
}
