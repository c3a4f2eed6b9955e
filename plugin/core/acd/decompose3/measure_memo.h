// Measures of part meshes kept for the rest of one solid's search. cut_search = thorough grows two cut
// trees of the solid; they share their first cuts and many subtrees, and at each node they share they
// try the same planes on the same mesh, so the same parts would be measured again. A measure is a
// function of the part's mesh (with tau and the cavity option, which are part of the key), so a kept one
// stands for one made anew: the parts are the same with the memo or without, only sooner. Measures are
// kept while the faces they describe stay within a budget: the first ones, the trees' shared top.
#pragma once

#include "acd/decompose3/decompose.h"
#include "acd/mesh/parallel.h"

#include <cstdint>
#include <functional>

namespace acd {

class MeasureMemo
{
public:
	explicit MeasureMemo(size_t max_faces = 2000000) : max_faces(max_faces) {}

	// The measure kept for mesh `m` under (tau, keep_cavities), else make()'s, kept if the budget
	// allows. Safe to call from several threads: a measure another thread is making is waited for.
	MeasuredPtr find_or_make(const TriMesh& m, double tau, bool keep_cavities, const std::function<MeasuredPtr()>& make);

	size_t hits() const { return kept.hits(); }
	size_t size() const { return kept.size(); }

private:
	SharedResults<std::uint64_t, MeasuredPtr> kept;
	size_t                                    faces = 0;   // of the kept measures (changed under kept's lock)
	const size_t                              max_faces;
};

} // namespace acd
