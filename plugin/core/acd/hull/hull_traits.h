// The traits every convex hull here is built with: CGAL's own, as a type of their own.
// For its default traits CGAL's quickhull answers "is this point above that facet?" with a filter of its
// own whose last resort is GMP rationals (each product reduced by a gcd). Points on a cut's cap are
// coplanar to rounding, so that last resort runs for most of them and dominated the hulls' cost. Any
// other traits type takes CGAL's generic path, the kernel's Orientation_3, whose last resort is Mpzf
// (exact, no gcd). Both answer every test exactly, so the hull is the same.
#pragma once

#include <CGAL/Convex_hull_traits_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

namespace acd {

struct HullTraits
	: CGAL::Convex_hull_traits_3<CGAL::Exact_predicates_inexact_constructions_kernel,
	                             CGAL::Surface_mesh<CGAL::Exact_predicates_inexact_constructions_kernel::Point_3>, CGAL::Tag_true>
{};

} // namespace acd
