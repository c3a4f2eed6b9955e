#include "acd/prepare/wrap_solid.h"

#include "acd/prepare/alpha_wrap.h"
#include "acd/prepare/fill_holes.h"
#include "acd/prepare/winding_caps.h"
#include "acd/mesh/nearest.h"
#include "acd/mesh/orient.h"
#include "acd/mesh/winding_number.h"
#include "acd/mesh/measures.h"
#include "acd/mesh/parallel.h"
#include "acd/solid/solid.h"
#include "acd/mesh/weld.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <tuple>
#include <unordered_map>

namespace acd {

std::vector<double> winding_numbers(const TriMesh& surface, const std::vector<Vec3>& points)
{
	return WindingNumber(surface).at(points);
}

namespace {

// Points of the input's bounding box that its winding number places inside (|w| > 1/2: the input's
// orientation is not trusted), drawn from a fixed seed so that the choice is repeatable.
std::vector<Vec3> interior_samples(const TriMesh& in, const WindingNumber& wn, int count)
{
	const Eigen::AlignedBox3d box = finite_box(in);
	std::vector<Vec3>         pts;
	if (box.isEmpty()) return pts;
	const Vec3                             lo = box.min(), hi = box.max();
	std::mt19937                           rng(12345);
	std::uniform_real_distribution<double> u(0.0, 1.0);
	for (int i = 0; i < count; ++i) pts.push_back(lo + (hi - lo).cwiseProduct(Vec3(u(rng), u(rng), u(rng))));
	const std::vector<double> w = wn.at(pts);
	std::vector<Vec3>         inside;
	for (size_t i = 0; i < pts.size(); ++i)
		if (std::abs(w[i]) > 0.6) inside.push_back(pts[i]);   // clearly inside: near a sheet |w| is about 1/2
	return inside;
}

double share_inside(const TriMesh& wrap, const std::vector<Vec3>& pts)
{
	if (pts.empty()) return 1;
	const std::vector<double> w = winding_numbers(wrap, pts);
	int                       n = 0;
	for (double x : w) n += x > 0.5;
	return double(n) / pts.size();
}

void keep(WrapSolidResult& r, TriMesh w, double alpha, double share)
{
	r.mesh   = std::move(w);
	r.alpha  = alpha;
	r.inside = share;
}

// The input's finite vertices that a face uses (all of them for a point cloud): a vertex no face uses,
// such as one left inside a hole cut out of a mesh, is no part of the surface.
std::vector<Vec3> used_vertices(const TriMesh& m)
{
	if (m.F.empty()) return finite_vertices(m);
	std::vector<char> used(m.V.size(), 0);
	for (const Tri& t : m.F)
		for (int v : t)
			if (v >= 0 && v < (int) m.V.size()) used[v] = 1;
	std::vector<Vec3> out;
	for (size_t i = 0; i < m.V.size(); ++i)
		if (used[i] && m.V[i].allFinite()) out.push_back(m.V[i]);
	return out;
}

// The input's distance tree, built beside the first wrap: the wrap runs on one thread, and on a big
// input the tree takes about half as long.
struct InputTree
{
	const TriMesh&                    input;
	std::unique_ptr<NearestOnSurface> near;
};

TriMesh wrap_beside(const TriMesh& m, double alpha, double offset, InputTree& t)
{
	TriMesh w;
	parallel_for(2, [&](size_t k) {
		if (k == 0) w = alpha_wrap(m, alpha, offset);
		else if (!t.near) t.near = std::make_unique<NearestOnSurface>(t.input);
	});
	return w;
}

WrapSolidResult& measured(WrapSolidResult& r, InputTree& t)
{
	if (!t.near) t.near = std::make_unique<NearestOnSurface>(t.input);
	std::tie(r.to_input, r.from_input) = wrap_distances(r.mesh, t.input, *t.near);
	return r;
}

// What the winding number and the wrap see of a big input: the weld with vertices within `cell` merged,
// so that about kWrapFaces faces are left (none merged, cell 0, when it has fewer). It lies within
// `cell` of the input, far within the wrap's alpha; the wrap's distances are measured on the input.
constexpr size_t kWrapFaces = 200000;
TriMesh          coarse_copy(const TriMesh& welded, double offset, double& cell)
{
	cell = 0;
	if (welded.F.size() <= kWrapFaces) return welded;
	cell = std::max(offset, std::sqrt(2 * surface_area(welded) / kWrapFaces));
	return weld(welded, cell);
}

} // namespace

std::pair<double, double> wrap_distances(const TriMesh& wrap, const TriMesh& input, const NearestOnSurface& near)
{
	return {near.farthest_on(wrap), NearestOnSurface(wrap).farthest(used_vertices(input))};
}

namespace {

// The input as given, or welded at 1e-5 of its size, when that is a valid solid; otherwise `welded` is
// the weld, for the measures that need shared vertices.
bool as_given_or_welded(const TriMesh& input, WrapSolidResult& r, TriMesh& welded)
{
	welded = input;
	try {
		r.solid = make_solid(input);
		r.mesh  = input;
		return true;
	} catch (const Error& e) {
		if (e.kind != Error::InvalidInput) throw;
		r.reason       = e.what();
		r.reason_code  = e.code;
		r.reason_count = e.count;
	}
	const double size   = extent(finite_vertices(input));
	int          merged = 0;
	if (size > 0) try {
			TriMesh w = weld(input, 1e-5 * size, &merged);
			welded    = w;
			if (merged > 0) {
				Solid s = make_solid(w);
				if (s.self_intersections == 0) {
					r.mesh   = std::move(w);
					r.welded = merged;
					r.solid  = std::move(s);
					return true;
				}
			}
		} catch (const Error& e) {
			if (e.kind != Error::InvalidInput) throw;
		}
	return false;
}

// The input wrapped together with its caps, kept if it holds the interior.
bool capped_wrap(const TriMesh& input, const WindingCaps& caps, const std::vector<Vec3>& inside, double alpha,
                 double offset, double min_inside, WrapSolidResult& r, InputTree& t)
{
	TriMesh with = input;
	append(with, caps.mesh);
	TriMesh      w     = wrap_beside(with, alpha, offset, t);
	const double share = share_inside(w, inside);
	++r.tries;
	if (share < min_inside) return false;
	keep(r, std::move(w), alpha, share);
	r.capped = true;
	return true;
}

// The faces from `first` on, with the vertices they use only.
TriMesh faces_from(const TriMesh& m, size_t first)
{
	TriMesh          out;
	std::vector<int> id(m.V.size(), -1);
	for (size_t f = first; f < m.F.size(); ++f) {
		Tri t;
		for (int k = 0; k < 3; ++k) {
			int& v = id[m.F[f][k]];
			if (v < 0) v = (int) out.V.size(), out.V.push_back(m.V[m.F[f][k]]);
			t[k] = v;
		}
		out.F.push_back(t);
	}
	return out;
}

// The weld with its holes filled (fill_holes), kept when that is a valid solid that does not cross itself.
// Its distance to the input is the patches': the rest is the input's own faces.
bool filled_solid(const TriMesh& welded, WrapSolidResult& r, InputTree& t)
{
	std::optional<FilledHoles> f;
	try {
		f = fill_holes(welded);
	} catch (const Error&) {
		throw;
	} catch (const std::exception&) {   // CGAL's own failure in a patch: the wrap closes the holes instead
		return false;
	}
	if (!f) return false;
	try {
		Solid s = make_solid(f->mesh);
		if (s.self_intersections > 0) return false;
		r.solid = std::move(s);
	} catch (const Error& e) {
		if (e.kind != Error::InvalidInput) throw;
		return false;
	}
	if (!t.near) t.near = std::make_unique<NearestOnSurface>(t.input);
	r.to_input   = t.near->farthest_on(faces_from(f->mesh, f->first_patch));
	r.from_input = NearestOnSurface(f->mesh).farthest(used_vertices(t.input));
	r.mesh       = std::move(f->mesh);
	r.filled     = f->holes;
	r.on_planes  = f->planar;
	r.wrapped    = false;
	return true;
}

} // namespace

WrapSolidResult wrap_solid(const TriMesh& input, double alpha, double offset, double max_alpha, double min_inside,
                           double max_cap_share, bool fill)
{
	WrapSolidResult r;
	TriMesh         welded;
	if (as_given_or_welded(input, r, welded)) return r;
	// Too few interior samples (a point cloud, a sheet, faces that cancel) cannot tell a skin from a
	// solid: the first wrap is kept. Patches turned against their neighbours would turn the winding
	// number inside out about them.
	TriMesh coarse = coarse_copy(welded, offset, r.coarse_cell);
	orient_patches(coarse);
	const WindingNumber     wn(coarse);
	const std::vector<Vec3> inside = interior_samples(coarse, wn, 512);
	const bool              judge  = inside.size() >= 16;
	r.wrapped = true;
	InputTree tree{input, nullptr};
	// The caps tell the openings: none wider than alpha, and the plain wrap closes them; wider ones, and
	// it would slip inside, unless they span so much (over max_cap_share of the level set, or farther
	// than max_alpha from the input) that the input is an open shell (a bowl, a tube, a helmet).
	std::optional<WindingCaps> caps;
	if (judge) caps = winding_caps(coarse, wn, NearestOnSurface(coarse), alpha / 2);
	const double reach = caps ? caps->reach : 0;
	r.cap_share        = caps ? caps->cap_share : 0;
	const bool shell   = caps && (r.cap_share > max_cap_share || reach > max_alpha);
	const bool wide    = caps && !shell && reach > alpha;
	if (fill && caps && !shell && filled_solid(welded, r, tree)) return r;
	if (wide && capped_wrap(coarse, *caps, inside, alpha, offset, min_inside, r, tree)) return measured(r, tree);
	keep(r, wrap_beside(coarse, alpha, offset, tree), alpha, 1.0);
	++r.tries;
	if (judge) r.inside = share_inside(r.mesh, inside);
	if (judge && !shell && !wide && r.inside < min_inside && capped_wrap(coarse, *caps, inside, alpha, offset, min_inside, r, tree))
		return measured(r, tree);
	// Should the caps not hold the interior either, coarser wraps are tried; when none up to max_alpha
	// does, the first wrap, the input's skin, is nearer to it than any coarse blob.
	for (double a = 2 * alpha; judge && !shell && r.inside < min_inside && a <= max_alpha * (1 + 1e-9); a *= 2) {
		TriMesh      w     = alpha_wrap(coarse, a, offset);
		const double share = share_inside(w, inside);
		++r.tries;
		if (share >= min_inside) keep(r, std::move(w), a, share);
	}
	r.skin = !judge || r.inside < min_inside;
	return measured(r, tree);
}

} // namespace acd
