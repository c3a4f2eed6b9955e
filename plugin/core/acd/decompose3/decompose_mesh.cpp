#include "acd/decompose3/decompose_mesh.h"

#include <algorithm>

namespace acd {

MeshDecomposition decompose_mesh(const TriMesh& mesh, const PrepareOptions& prepare, const OptionsFor& options_for)
{
	MeshDecomposition r;
	r.prepared          = prepare_solid(mesh, prepare);
	r.options           = options_for(r.prepared);
	const bool as_given = prepare.mode == Preprocessing::Auto && r.prepared.done == PreparedSolid::AsGiven;
	if (!as_given) {
		r.d = decompose(r.prepared.solid, r.options);
		return r;
	}
	DecomposeOptions bounded = r.options;
	const double     limit   = r.options.time_limit_seconds;
	const long       crossings = r.prepared.solid.self_intersections;
	if (crossings > 0) bounded.time_limit_seconds = std::min(limit > 0 ? limit : kSelfCrossingTry, kSelfCrossingTry);
	// A solid that crosses itself is searched as it is (its proxy would cross too, proxy_search.h);
	// a large one would use up the try: it is wrapped at once.
	if (crossings > 0 && (long) r.prepared.solid.mesh.F.size() > kSelfCrossingFaces)
		r.fallback = "the mesh intersects itself (" + std::to_string(crossings) + " face pairs) and has more than " +
		             std::to_string(kSelfCrossingFaces) + " faces";
	else
		try {
			r.d = decompose(r.prepared.solid, bounded);
			if (crossings == 0 || r.d.tau_convex()) return r;
			r.fallback = "the mesh intersects itself (" + std::to_string(crossings) + " face pairs) and its parts as given are not all within tau";
		} catch (const Error& e) {
			if (e.code != Error::OpenPart) throw;
			r.fallback = e.what();
		}
	PrepareOptions wrap = prepare;
	wrap.mode           = Preprocessing::AlphaWrap;
	r.prepared          = prepare_solid(mesh, wrap);
	r.options           = options_for(r.prepared);
	r.d                 = decompose(r.prepared.solid, r.options);
	return r;
}

} // namespace acd
