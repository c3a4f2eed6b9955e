// When a hole (a solid's cavity, a polygon's hole) is cut: the same choice for both dimensions.
#pragma once

namespace acd {

enum class HoleOrder
{
	First,        // the paper (a hole's concavity is infinite): every cavity is cut before any notch
	ByConcavity   // a cavity's concavity is its depth below the hull; cut in turn with the notches
};

} // namespace acd
