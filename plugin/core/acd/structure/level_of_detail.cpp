// Level of detail from a finished tree, and a subtree's solid rebuilt from its leaves.
#include "acd/decompose3/decompose.h"
#include "acd/structure/level_of_detail.h"
#include "acd/hull/hull_reach.h"
#include "acd/solid/rims.h"
#include "acd/mesh/measures.h"
#include "acd/mesh/weld.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

namespace acd {

namespace {

std::vector<int> level_where(const Decomposition& D, const std::function<bool(int)>& whole, bool merged)
{
	std::vector<int> out, stack{0};
	while (!stack.empty()) {
		const int id = stack.back();
		stack.pop_back();
		if (D.nodes[id].leaf() || whole(id)) out.push_back(id);
		else stack.insert(stack.end(), {D.nodes[id].child[1], D.nodes[id].child[0]});
	}
	// A merged part stands for its leaves where the level keeps all of them as they are.
	std::set<int> level(out.begin(), out.end());
	for (int m = 0; m < (int) D.nodes.size() && merged; ++m) {
		const std::vector<int>& leaves = D.nodes[m].merged;
		if (leaves.empty() || !std::all_of(leaves.begin(), leaves.end(), [&](int l) { return level.count(l); })) continue;
		for (int l : leaves) level.erase(l);
		level.insert(m);
	}
	out.assign(level.begin(), level.end());
	std::sort(out.begin(), out.end(), [&](int a, int b) { return D.nodes[a].path < D.nodes[b].path; });
	return out;
}

bool within_by_notches(const Decomposition& D, const Node& n, double tau)
{
	return n.concavity <= tau && !n.solids && (n.cavities == 0 || D.kept_cavities > 0);
}

} // namespace

std::vector<int> level_of_detail(const Decomposition& D, double tau, int depth)
{
	return level_where(D, [&](int id) {
		const Node& n = D.nodes[id];
		return depth >= 0 ? (int) n.path.size() - 1 >= depth : within_by_notches(D, n, tau);
	}, depth < 0);
}

std::vector<int> level_of_detail_within(const Decomposition& D, double tau, const std::vector<TriMesh>& hull)
{
	return level_where(D, [&](int id) {
		if (!within_by_notches(D, D.nodes[id], tau)) return false;
		const TriMesh    solid = rebuild_solid(D, id);
		const ConvexHull h(id < (int) hull.size() && !hull[id].V.empty() ? hull[id].V : solid.V);
		const HullReach  r = hull_reach(solid, h, std::vector<char>(h.facets(), 1), tau, 0.01 * tau);
		return r.upper <= 1.01 * tau;
	}, true);
}

namespace {

// The leaves below node `id` and the planes of the cuts between them.
void subtree(const Decomposition& D, int id, std::vector<int>& leaves, std::vector<Plane>& cuts)
{
	std::vector<int> stack{id};
	while (!stack.empty()) {
		const Node& n = D.nodes[stack.back()];
		const int   k = stack.back();
		stack.pop_back();
		if (n.leaf()) leaves.push_back(k);
		else {
			if (n.has_plane) cuts.push_back(n.plane);
			stack.push_back(n.child[0]);
			stack.push_back(n.child[1]);
		}
	}
}

// The leaves welded (cap vertices are bit-identical copies on both sides), cap faces dropped.
TriMesh weld_without_caps(const Decomposition& D, const std::vector<int>& leaves, const std::vector<Plane>& cuts,
                          double eps)
{
	TriMesh   all;
	ExactWeld weld(all.V);
	for (int l : leaves) {
		const TriMesh&         m     = D.nodes[l].mesh;
		const std::vector<int> id_of = weld.add(m);
		for (const Tri& t : m.F)
			if (std::none_of(cuts.begin(), cuts.end(), [&](const Plane& pl) { return pl.holds(m.V, t, eps); }))
				all.F.push_back({id_of[t[0]], id_of[t[1]], id_of[t[2]]});
	}
	return all;
}

} // namespace

TriMesh rebuild_solid(const Decomposition& D, int id)
{
	if (!D.nodes[id].merged.empty()) return D.nodes[id].mesh;   // a merged part is kept whole
	std::vector<int>   leaves;
	std::vector<Plane> cuts;
	subtree(D, id, leaves, cuts);
	if (leaves.size() == 1) return D.nodes[leaves[0]].mesh;
	std::vector<Vec3> pts;
	for (int l : leaves)
		for (const Vec3& p : D.nodes[l].mesh.V) pts.push_back(p);
	const double eps = 1e-9 * extent(pts);
	TriMesh      all = weld_without_caps(D, leaves, cuts, eps);
	close_rims(all, eps);
	return compacted(all);
}

} // namespace acd
