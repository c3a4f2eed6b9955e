// CMeshO <-> the core's TriMesh.
#pragma once

#include <acd/mesh/mesh.h>
#include <common/ml_document/cmesh.h>

namespace acdml {

// Live vertices and faces of `m`; `vertex_index` maps TriMesh vertex -> CMeshO vertex index;
// `edges` receives the live edges (TriMesh vertex indices).
acd::TriMesh to_trimesh(const CMeshO& m, std::vector<int>* vertex_index = nullptr,
                        std::vector<std::array<int, 2>>* edges = nullptr);
// Replaces `m` with `t`'s vertices and faces, and `edges` between them.
void from_trimesh(const acd::TriMesh& t, CMeshO& m, const std::vector<std::array<int, 2>>& edges = {});

} // namespace acdml
