// Approx_CD's recursion, shared by the 3D and 2D drivers: the open nodes in a work queue, most
// concave first, cut one at a time until every node is done or a limit stops it; progress and
// cancelling. The dimension supplies the cut. (Internal header of the core.)
#pragma once

#include "acd/mesh/mesh.h"   // Error
#include "acd/recursion/hole_order.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <queue>
#include <string>
#include <vector>

namespace acd {

struct RecursionLimits
{
	double     tau = 0;              // a node is done at concavity <= tau ...
	bool       keep_holes = false;   // ... and no hole (cavity) left, unless holes are kept
	HoleOrder  hole_order = HoleOrder::First;
	int        max_parts = 0;        // 0 = unbounded
	double     time_limit_seconds = 0;
	size_t     max_depth = 0;        // a node deeper than this (its path length) stays a leaf, uncut
	std::function<bool(int, const char*)> progress;
};

// The limits from a dimension's options (tau, hole_order, max_parts, time_limit_seconds, progress).
template <class Options> RecursionLimits limits_from(const Options& o, bool keep_holes, size_t max_depth)
{
	RecursionLimits l;
	l.tau                = o.tau;
	l.keep_holes         = keep_holes;
	l.hole_order         = o.hole_order;
	l.max_parts          = o.max_parts;
	l.time_limit_seconds = o.time_limit_seconds;
	l.max_depth          = max_depth;
	l.progress           = o.progress;
	return l;
}

// `NodeT` has path, concavity and uncut; holes_in(node) counts its holes (found by argument lookup).
// `Cutter` has cut(id), which returns the parts it added (1 for a split, 0 otherwise) and may push
// nodes back, and forget(id), called for a node given up on.
template <class NodeT> class Recursion
{
public:
	Recursion(std::vector<NodeT>& nodes, const RecursionLimits& limits)
	    : nodes(nodes), lim(limits), open(Worse{this}), start(std::chrono::steady_clock::now())
	{
	}

	bool needs_cut(const NodeT& n) const { return n.concavity > lim.tau || (!lim.keep_holes && holes_in(n) > 0); }

	void push(int id) { open.push(id); }

	// The first nodes to cut, measured: the progress runs from the worst of them to tau.
	void start_with(const std::vector<int>& roots)
	{
		for (int id : roots) {
			c0 = std::max(c0, nodes[id].concavity);
			push(id);
		}
		parts = (int) roots.size();
	}

	template <class Cutter> void run(Cutter& cutter)
	{
		while (!open.empty()) {
			const int id = open.top();
			if (!needs_cut(nodes[id]) || limit_reached()) break;   // every open node is done, or a bound
			open.pop();
			// A cut that keeps failing to lower the concavity must not recurse forever.
			if (nodes[id].path.size() > lim.max_depth) {
				nodes[id].uncut = true;
				cutter.forget(id);
				continue;
			}
			report(id);
			parts += cutter.cut(id);
		}
		if (lim.progress) lim.progress(100, "Decomposition done");
	}

	// Into the finished tree: which limit stopped the recursion, and (holes kept) the holes left in
	// its leaves.
	template <class Tree> void record(Tree& D, int& kept_holes) const
	{
		D.max_parts_reached  = max_parts_reached;
		D.time_limit_reached = time_limit_reached;
		if (lim.keep_holes)
			for (const NodeT& n : nodes)
				if (n.leaf()) kept_holes += holes_in(n);
	}

	bool max_parts_reached = false, time_limit_reached = false;

private:
	// Open nodes, most concave first (ties by path), so a max_parts bound cuts the worst notches;
	// with hole_order = first, nodes holding a hole come before all others (infinite concavity).
	struct Worse
	{
		const Recursion* r;
		bool             operator()(int a, int b) const
		{
			const NodeT &A = r->nodes[a], &B = r->nodes[b];
			if (r->needs_cut(A) != r->needs_cut(B)) return !r->needs_cut(A);
			if (r->lim.hole_order == HoleOrder::First && !r->lim.keep_holes && (holes_in(A) > 0) != (holes_in(B) > 0))
				return holes_in(A) == 0;
			if (A.concavity != B.concavity) return A.concavity < B.concavity;
			return A.path > B.path;
		}
	};

	std::vector<NodeT>&                                 nodes;
	const RecursionLimits                               lim;
	std::priority_queue<int, std::vector<int>, Worse>   open;
	const std::chrono::steady_clock::time_point         start;
	double                                              c0    = lim.tau;
	int                                                 parts = 0;

	bool limit_reached()
	{
		if (lim.max_parts > 0 && parts >= lim.max_parts) return max_parts_reached = true;
		if (lim.time_limit_seconds > 0 &&
		    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > lim.time_limit_seconds)
			return time_limit_reached = true;
		return false;
	}

	// Progress on a log scale from the first concavity down to tau (a node cut for a hole alone may
	// be within tau already: it counts as at tau).
	void report(int id) const
	{
		if (!lim.progress) return;
		const double cur = std::max(nodes[id].concavity, lim.tau);
		const int    pct = (int) (100 * std::log(c0 / cur) / std::max(1e-12, std::log(c0 / lim.tau)));
		char         msg[96];
		std::snprintf(msg, sizeof msg, "Decomposing: %d parts, worst concavity %.3g tau", parts, cur / lim.tau);
		if (!lim.progress(std::clamp(pct, 0, 99), msg)) throw Error(Error::Cancelled, "The decomposition was cancelled.");
	}
};

// What a dimension's driver holds: its options, the tree, and the recursion over the tree's nodes.
// `Cutter` (the derived driver) has cut(id) and forget(id); `kept` names the tree's count of holes
// left in parts.
template <class Cutter, class Tree, class Options> class Driving
{
protected:
	using NodeT = typename decltype(Tree::nodes)::value_type;

	Driving(const Options& opt, bool keep, size_t max_depth) : opt(opt), keep(keep), rec(D.nodes, limits_from(opt, keep, max_depth))
	{
		D.tau = opt.tau;
	}

	// Cut from the given first nodes (already measured) until done; the finished tree.
	Tree finish(const std::vector<int>& roots, int Tree::*kept)
	{
		rec.start_with(roots);
		rec.run(static_cast<Cutter&>(*this));
		rec.record(D, D.*kept);
		return std::move(D);
	}

	const Options&   opt;
	const bool       keep;
	Tree             D;
	Recursion<NodeT> rec;
};

} // namespace acd
