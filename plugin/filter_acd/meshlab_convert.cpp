#include "meshlab_convert.h"

#include <vcg/complex/allocate.h>

namespace acdml {

acd::TriMesh to_trimesh(const CMeshO& m, std::vector<int>* vertex_index, std::vector<std::array<int, 2>>* edges)
{
	acd::TriMesh     t;
	std::vector<int> remap(m.vert.size(), -1);
	for (size_t i = 0; i < m.vert.size(); ++i) {
		if (m.vert[i].IsD()) continue;
		remap[i] = (int) t.V.size();
		const auto& p = m.vert[i].cP();
		t.V.emplace_back(p[0], p[1], p[2]);
		if (vertex_index) vertex_index->push_back((int) i);
	}
	for (const auto& f : m.face) {
		if (f.IsD()) continue;
		acd::Tri tri;
		for (int k = 0; k < 3; ++k) tri[k] = remap[vcg::tri::Index(m, f.cV(k))];
		t.F.push_back(tri);
	}
	if (edges)
		for (const auto& e : m.edge)
			if (!e.IsD()) edges->push_back({remap[vcg::tri::Index(m, e.cV(0))], remap[vcg::tri::Index(m, e.cV(1))]});
	return t;
}

void from_trimesh(const acd::TriMesh& t, CMeshO& m, const std::vector<std::array<int, 2>>& edges)
{
	m.Clear();
	auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(m, t.V.size());
	for (const auto& p : t.V) (vi++)->P() = CMeshO::CoordType(p.x(), p.y(), p.z());
	auto fi = vcg::tri::Allocator<CMeshO>::AddFaces(m, t.F.size());
	for (const auto& f : t.F) {
		for (int k = 0; k < 3; ++k) fi->V(k) = &m.vert[f[k]];
		++fi;
	}
	if (!edges.empty()) {
		auto ei = vcg::tri::Allocator<CMeshO>::AddEdges(m, edges.size());
		for (const auto& e : edges) {
			ei->V(0) = &m.vert[e[0]];
			ei->V(1) = &m.vert[e[1]];
			++ei;
		}
	}
}

} // namespace acdml
