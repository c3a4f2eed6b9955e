// The merge stage after the cuts: neighbouring parts whose union is still tau-convex become one part.
// The cuts are made top-down for the most concave notch, so two leaves split high in the tree for a
// notch elsewhere stay apart although together they are convex; merging gives them back.
#pragma once

#include "acd/decompose3/decompose.h"

#include <functional>
#include <memory>

namespace acd {

// Leaves sharing a cut's cap (with positive area) are neighbours; under MergeMeasure::HullDistance so
// are leaves of different solids of the input (an assembly's pieces, split apart first) whose boxes come
// within twice the certificate's bar of each other. Greedily, the neighbouring pair whose union is least
// concave is merged, while the union has no cavity and joins no shells but along the cuts (two solids
// side by side stay two shells of one part) and passes the certificate `measure` names: its hull's
// reach beyond it certified within tau (to 1% of tau); with MergeMeasure::Concavity also the paper's
// concavity at most tau, the cuts' own certificate. A part merged by its hull alone is marked
// `hull_certified`. Unions are exact (CGAL corefinement), so the parts stay an exact partition of the
// solid. The cut tree is kept as it is; each merged part is appended as a node whose `merged` lists the
// leaves it unites, and those leaves point to it with `part`. Leaves over
// tau (uncut) are never merged. With `seconds` > 0 merging stops once that long has passed (the parts
// stay a certified partition; D.merge_time_limit_reached says so). Returns the number of merges.
//
// A union's hull reach, the certificate's costly half, is measured only once the union comes first in
// line to merge (most never do: a neighbour of theirs merges first); the line is the same, so are the
// merges.
//
// `memo`, when given, keeps every union measured, keyed by the two parts' contents and the cuts along
// and between them, and reuses them: two merges over cut trees of one solid that share their first cuts
// (cut_search's two searches) measure each shared union once. The parts are the same with or without.
class MergeMemo
{
public:
	MergeMemo();
	~MergeMemo();
	size_t size() const;         // unions measured and kept
	size_t candidates() const;   // of those, the unions that passed the certificate but for the reach
	size_t reaches() const;      // and of those, the unions whose hull's reach was measured
	struct Unions;
	std::unique_ptr<Unions> unions;
};
int merge_parts(Decomposition& D, double tau, const std::function<bool(int, const char*)>& progress = {},
                double seconds = 0, MergeMemo* memo = nullptr, MergeMeasure measure = MergeMeasure::HullDistance);

// The merge again, from the parts as they stand (merged parts included) rather than the leaves: for a
// tree grown in pieces, each merged on its own (the proxy search's parts searched again), so that the
// pieces merge across. Only the neighbouring parts (part nodes a, b) for which `first(a, b)` holds are
// measured at the start (the rest were measured before); a merged part united further is dropped from
// D.nodes (the ids after it shift). Returns the merges made; D.merges counts them too.
int merge_parts_further(Decomposition& D, double tau, const std::function<bool(int, int)>& first,
                        const std::function<bool(int, const char*)>& progress = {}, double seconds = 0,
                        MergeMemo* memo = nullptr, MergeMeasure measure = MergeMeasure::HullDistance);

// D without the nodes marked in `drop` (none of them a tree node another refers to), ids renumbered.
void drop_nodes(Decomposition& D, const std::vector<char>& drop);

// Neighbouring leaves (node ids a < b): on the two sides of the cut at node `cut`, their caps on its
// plane overlapping with positive area.
struct LeafContact
{
	int a = -1, b = -1, cut = -1;
};
std::vector<LeafContact> neighbouring_leaves(const Decomposition& D);

} // namespace acd
