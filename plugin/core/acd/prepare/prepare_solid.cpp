#include "acd/prepare/prepare_solid.h"
#include "acd/mesh/measures.h"
#include "acd/prepare/alpha_wrap.h"
#include "acd/prepare/wrap_solid.h"

#include <chrono>
#include <cstdio>
#include <tuple>

namespace acd {

const std::vector<PreprocessingMode>& preprocessing_modes()
{
	static const std::vector<PreprocessingMode> table = {
		{Preprocessing::None, "none",
		 "the mesh must be a closed, 2-manifold, oriented solid that does not intersect itself"},
		{Preprocessing::AlphaWrap, "alpha_wrap",
		 "first wrap it with CGAL's 3D alpha wrapping, which turns open, non-manifold, self-intersecting meshes, "
		 "triangle soups and point clouds into one closed solid (the parts then decompose the wrap, which lies "
		 "about wrap_offset outside the input)"},
		{Preprocessing::Auto, "auto",
		 "as given when it is a valid solid, else welded (vertices within 1e-5 of its size) if that makes it one, "
		 "else, for a surface with holes that is not an open shell, its holes filled (a hole whose rim runs on a few "
		 "planes, as in a CAD export missing faces, on those planes; any other by CGAL's hole filling, faired: the "
		 "patches continue the surface's curvature) if that makes a solid that does not cross itself, "
		 "else alpha wrapped; a wrap that slipped inside through wider holes (a hollow skin) is made again with "
		 "caps across the openings where the input's generalized winding number is 1/2, so that they close along "
		 "the surface; an open shell (a sheet, a bowl, a helmet) keeps its skin. A solid that crosses itself is "
		 "decomposed as given within 120 s and wrapped when its parts fall short of tau"},
	};
	return table;
}

namespace {

double finite_size(const TriMesh& mesh)
{
	const std::vector<Vec3> finite = finite_vertices(mesh);
	if (finite.empty()) throw Error(Error::InvalidInput, "The mesh has no vertex with finite coordinates.");
	return enclosing_diameter(finite);
}

void wrapped(PreparedSolid& p, TriMesh wrap, double alpha, double share)
{
	p.solid       = make_solid(wrap);
	p.done        = PreparedSolid::Wrapped;
	p.alpha       = alpha;
	p.alpha_share = share;
}

} // namespace

PreparedSolid prepare_solid(const TriMesh& mesh, const PrepareOptions& o)
{
	const auto    t0 = std::chrono::steady_clock::now();
	PreparedSolid p;
	p.faces_in = mesh.F.size();
	if (o.mode == Preprocessing::None) p.solid = make_solid(mesh);
	else {
		p.size   = finite_size(mesh);
		p.offset = o.offset * p.size;
		if (o.mode == Preprocessing::AlphaWrap) {
			TriMesh wrap = alpha_wrap(mesh, o.alpha * p.size, p.offset);
			std::tie(p.to_input, p.from_input) = wrap_distances(wrap, mesh, NearestOnSurface(mesh));
			wrapped(p, std::move(wrap), o.alpha * p.size, o.alpha);
			p.tries = 1;
		}
		else {
			WrapSolidResult w = wrap_solid(mesh, o.alpha * p.size, p.offset, o.max_alpha * p.size);
			p.reason = w.reason;
			p.reason_code  = w.reason_code;
			p.reason_count = w.reason_count;
			p.tries  = w.tries;
			p.inside = w.inside;
			p.capped = w.capped;
			p.skin   = w.skin;
			p.cap_share  = w.cap_share;
			p.to_input   = w.to_input;
			p.from_input = w.from_input;
			if (w.wrapped) wrapped(p, std::move(w.mesh), w.alpha, w.alpha / p.size);
			else {
				p.solid  = w.solid ? std::move(*w.solid) : make_solid(w.mesh);
				p.done   = w.filled > 0 ? PreparedSolid::Filled
				         : w.welded > 0 ? PreparedSolid::Welded : PreparedSolid::AsGiven;
				p.welded = w.welded;
				p.filled = w.filled;
				p.on_planes = w.on_planes;
			}
		}
	}
	if (o.refuse_self_intersection && p.solid.self_intersections > 0)
		throw Error(Error::InvalidInput, "The mesh intersects itself.", Error::SelfIntersection, p.solid.self_intersections);
	p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	return p;
}

std::string describe(const PreparedSolid& p)
{
	char buf[64];
	if (p.done == PreparedSolid::Welded) std::snprintf(buf, sizeof buf, "welded %d vertices", p.welded);
	else if (p.done == PreparedSolid::Filled) std::snprintf(buf, sizeof buf, "%d holes filled", p.filled);
	else if (p.done == PreparedSolid::Wrapped)
		std::snprintf(buf, sizeof buf, "alpha_wrap %.3g%%%s", 100 * p.alpha_share,
		              p.capped ? ", openings capped" : p.skin ? ", a skin" : "");
	else std::snprintf(buf, sizeof buf, "as given");
	return buf;
}

} // namespace acd
