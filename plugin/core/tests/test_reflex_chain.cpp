#include "acd/decompose3/decompose.h"
#include "acd/mesh/topology.h"
#include "acd/mesh/measures.h"
#include "acd/solid/solid.h"
#include "shapes.h"
#include "check.h"

using namespace acd;

TEST_CASE("a step's reflex ring is one closed planar chain")
{
	// Three coaxial cylinders (r 3, 2, 1.2), 48 facets: the steps' inner corners are rings of 48.
	const int     nu    = 48;
	const TriMesh shaft = shapes::lathe({{0, 0}, {3, 0}, {3, 10}, {2, 10}, {2, 20}, {1.2, 20}, {1.2, 26}, {0, 26}}, nu);
	const Topology t(shaft);
	const int     first = 1 + 2 * nu;   // profile point 3, (r 2, z 10): the first ring's vertex 0
	REQUIRE(shaft.V[first].z() == 10);
	const std::vector<int> chain = reflex_chain(shaft, t, first, (shaft.V[first + 1] - shaft.V[first]).normalized(), 0.7);
	CHECK(chain.size() == nu);
	std::vector<Vec3> pts;
	for (int v : chain) {
		CHECK(shaft.V[v].z() == 10);
		pts.push_back(shaft.V[v]);
	}
	const auto n = chain_plane_normal(pts);
	REQUIRE(n);
	CHECK(std::abs(n->z()) > 1 - 1e-9);
	// The outer corners (r 3 at z 10) are convex: no chain starts there.
	CHECK(reflex_chain(shaft, t, 1 + nu, (shaft.V[2 + nu] - shaft.V[1 + nu]).normalized(), 0.7).size() == 1);
}

TEST_CASE("a straight or ragged chain spans no rim plane")
{
	std::vector<Vec3> line, ragged, arc;
	for (int i = 0; i < 20; ++i) {
		line.emplace_back(i, 2 * i, -i);
		const double a = 0.2 * i;
		arc.emplace_back(std::cos(a), std::sin(a), 0.5);
		ragged.emplace_back(std::cos(a), std::sin(a), 0.05 * (i % 3));
	}
	CHECK(!chain_plane_normal(line));
	CHECK(!chain_plane_normal(ragged));
	REQUIRE(chain_plane_normal(arc));
	CHECK(std::abs(chain_plane_normal(arc)->z()) > 1 - 1e-9);
	CHECK(!chain_plane_normal({arc[0], arc[1], arc[2]}));   // too few to tell a plane
}

TEST_CASE("a rounded groove is cut across its rims, not in wedges")
{
	// A pulley: two flanges (r 3 and 3.6) around a groove whose half-round profile (r 0.8, 8 facets)
	// turns by 22.5 degrees per ring, under the 30 degrees of a sharp edge: no face plane is tried
	// there, and the bisector of a ring's faces leans with the profile.
	std::vector<Eigen::Vector2d> profile{{0, 0}, {3, 0}};
	for (int k = 0; k <= 8; ++k) {
		const double a = M_PI * k / 8;
		profile.emplace_back(3 - 0.8 * std::sin(a), 2 - 0.8 * std::cos(a));
	}
	profile.emplace_back(3.6, 3);
	profile.emplace_back(3.6, 4);
	profile.emplace_back(0, 4);
	const TriMesh pulley = shapes::lathe(profile, 48);
	const double  tau    = 0.05 * extent(pulley.V);
	DecomposeOptions o;
	o.tau                 = tau;
	o.cut_plane_selection = CutPlaneSelection::BisectorOrFace;
	const Decomposition rim = decompose(make_solid(pulley), o);
	o.cut_plane_selection   = CutPlaneSelection::Bisector;
	const Decomposition bis = decompose(make_solid(pulley), o);
	MESSAGE("pulley: " << rim.leaves().size() << " parts across its rims, " << bis.leaves().size() << " by the bisector");
	CHECK(rim.leaves().size() < bis.leaves().size());
	double vol = 0;
	for (int i : rim.leaves()) {
		const Node& n = rim.nodes[i];
		vol += make_solid(n.mesh).volume;   // closed and manifold, or it throws
		CHECK(n.concavity <= tau);
		CHECK(n.hull_distance_bound <= 1.01 * tau);
		if (n.parent >= 0) CHECK(std::abs(rim.nodes[n.parent].plane.n.z()) > 0.999);   // every cut across the axis
	}
	CHECK_NEAR(vol / signed_volume(pulley), 1.0, 1e-9);
}
