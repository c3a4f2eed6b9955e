// A mesh as the user gives it, prepared and decomposed: the entry the MeshLab filters, the command line
// and the benchmarks share, so that every one of them prepares a mesh by the same policy.
#pragma once

#include "acd/decompose3/decompose.h"
#include "acd/prepare/prepare_solid.h"

#include <functional>
#include <string>

namespace acd {

struct MeshDecomposition
{
	PreparedSolid prepared;
	Decomposition d;
	DecomposeOptions options;   // what d was cut with
	std::string   fallback;   // why the solid as given was wrapped after all (empty: it was not)
};

// prepare_solid, then decompose. Under Preprocessing::Auto a valid solid that crosses itself is cut
// as given for at most kSelfCrossingTry seconds (cuts through a crossing can peel slivers for long);
// when a cut opens a part there, or its parts fall short of tau, it is alpha wrapped and cut again. One
// with more than kSelfCrossingFaces faces is wrapped without the try (searched as it is, it would use
// the try up).
// `options_for` gives the options for a prepared solid (tau as a share of its size, say); it is called
// again for the wrap when the solid as given is given up.
using OptionsFor = std::function<DecomposeOptions(const PreparedSolid&)>;
MeshDecomposition decompose_mesh(const TriMesh& mesh, const PrepareOptions& prepare, const OptionsFor& options_for);

constexpr double kSelfCrossingTry   = 120;
constexpr long   kSelfCrossingFaces = 100000;

} // namespace acd
