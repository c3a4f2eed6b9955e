// CMeshO <-> the core's TriMesh.
#pragma once

#include <acd/mesh.h>
#include <common/ml_document/cmesh.h>

namespace acdml {

// Live vertices and faces of `m`; `vertex_index` maps TriMesh vertex -> CMeshO vertex index.
acd::TriMesh to_trimesh(const CMeshO& m, std::vector<int>* vertex_index = nullptr);
void         from_trimesh(const acd::TriMesh& t, CMeshO& m);

} // namespace acdml
