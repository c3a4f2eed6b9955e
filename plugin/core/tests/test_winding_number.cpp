#include "acd/mesh/winding_number.h"
#include "shapes.h"
#include "check.h"

#include <random>

using namespace acd;

namespace {

// Every face's solid angle summed, without a tree (Van Oosterom and Strackee), over 4 pi.
double brute_force(const TriMesh& m, const Vec3& q)
{
	double sum = 0;
	for (const Tri& t : m.F) {
		const Vec3   a = m.V[t[0]] - q, b = m.V[t[1]] - q, c = m.V[t[2]] - q;
		const double la = a.norm(), lb = b.norm(), lc = c.norm();
		sum += 2 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
	}
	return sum / (4 * M_PI);
}

} // namespace

TEST_CASE("the fast winding number follows the exact sum on open and closed surfaces")
{
	TriMesh torus = shapes::torus(1.0, 0.35, 96, 48), open;
	open.V        = torus.V;
	for (const Tri& t : torus.F)   // a window cut into the tube
		if ((torus.V[t[0]] + torus.V[t[1]] + torus.V[t[2]]).x() / 3 < 0.9) open.F.push_back(t);
	std::mt19937                           rng(7);
	std::uniform_real_distribution<double> u(-1.6, 1.6);
	for (const TriMesh* m : {&torus, &open}) {
		const WindingNumber wn(*m);
		std::vector<Vec3>   q;
		for (int i = 0; i < 300; ++i) q.emplace_back(u(rng), u(rng), 0.3 * u(rng));
		const std::vector<double> fast = wn.at(q);
		double                    worst = 0;
		for (size_t i = 0; i < q.size(); ++i) {
			CHECK(fast[i] == wn.at(q[i]));   // the same in parallel as one by one
			worst = std::max(worst, std::abs(fast[i] - brute_force(*m, q[i])));
		}
		CHECK(worst < 0.04);   // dipoles seen from three radii away: a few percent near the surface
	}
	CHECK(WindingNumber(TriMesh{}).at(Vec3::Zero()) == 0);
}
