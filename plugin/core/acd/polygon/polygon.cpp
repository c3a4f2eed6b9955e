#include "acd/polygon/polygon.h"
#include "acd/polygon/geometry2.h"
#include "acd/mesh/parallel.h"
#include "acd/recursion/recursion.h"
#include "acd/mesh/measures.h"
#include "acd/recursion/hole_order.h"


#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <map>
#include <queue>
#include <set>
#include <sstream>

namespace acd {

// The recursion's hole count of a polygon node.
int holes_in(const Node2& n)
{
	return n.hole_count;
}

std::vector<int> Decomposition2::leaves() const
{
	std::vector<int> l;
	for (int i = 0; i < (int) nodes.size(); ++i)
		if (nodes[i].leaf()) l.push_back(i);
	std::sort(l.begin(), l.end(), [&](int a, int b) { return nodes[a].path < nodes[b].path; });
	return l;
}

double Decomposition2::max_leaf_concavity() const
{
	double c = 0;
	for (int i : leaves()) c = std::max(c, nodes[i].concavity);
	return c;
}

namespace {

// Principal axes of a hole's boundary (length-weighted, so the sampling does not matter) and its
// centre: columns of `axes` major first.
void hole_axes(const Loop2& H, Vec2& centre, Eigen::Matrix2d& axes)
{
	double          len = 0;
	Vec2            c   = Vec2::Zero();
	Eigen::Matrix2d M   = Eigen::Matrix2d::Zero();
	for (size_t i = 0; i < H.size(); ++i) {
		const Vec2 &a = H[i], &b = H[(i + 1) % H.size()];
		const double w = (b - a).norm();
		len += w;
		c += w * (a + b) / 2;
		M += w / 6 * (2 * a * a.transpose() + 2 * b * b.transpose() + a * b.transpose() + b * a.transpose());
	}
	c /= len;
	centre = c;
	Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(M / len - c * c.transpose());
	axes.col(0) = es.eigenvectors().col(1);
	axes.col(1) = es.eigenvectors().col(0);
}

struct Scored
{
	double conc = 0;   // a piece's concavity for scoring: notches, and holes by their depth
	int    holes = 0;
};

Scored score(const Polygon2& p, bool keep)
{
	const Concavity2 c = measure_concavity(p);
	Scored           s{c.max_concavity, (int) p.holes.size()};
	if (!keep)
		for (double d : c.hole_depth) s.conc = std::max(s.conc, d);
	return s;
}

Line2 line_through(const Vec2& p, const Vec2& dir)
{
	Line2 l;
	l.n = Vec2(-dir.y(), dir.x()).normalized();
	l.d = l.n.dot(p);
	return l;
}

// A candidate cut: from a point (an outer vertex, or -1 for a hole's centre) along a direction.
struct Cand
{
	Vec2 from, dir;
	int  vertex;
};

struct Trial2
{
	std::array<Polygon2, 2> parts;
	Vec2                    a, b;
	bool                    ok = false, crosses = false;
	double                  score = 0, sum = 0;
};

// One polygon's cut: its target (the most concave notch, or a hole), candidate lines, their trials.
struct Cut2
{
	int                 id = -1, hole = -1;
	std::vector<Cand>   cands;
	std::vector<Trial2> trials;
	bool                first_fit = false;
	int                 pick = -1;
};

// Algorithm 5.3 for a polygon with holes, as named stages; the recursion is the one 3D uses.
class Driver2 : public Driving<Driver2, Decomposition2, PolygonOptions>
{
public:
	explicit Driver2(const PolygonOptions& opt) : Driving(opt, opt.hole_handling == HoleCut::KeepHoles, kMaxDepth) {}

	Decomposition2 run(const Polygon2& poly) { return finish({add_node(poly, -1, "0")}, &Decomposition2::kept_holes); }

	int cut(int id)
	{
		Cut2 c;
		c.id = id;
		choose_target(c);
		if (c.hole >= 0) hole_lines(c);
		else notch_lines(c);
		try_lines(c);
		pick_line(c);
		return accept(c);
	}

	void forget(int) {}

private:
	std::vector<Concavity2> measured;

	int add_node(Polygon2 p, int parent, const std::string& path)
	{
		Node2 n;
		n.parent           = parent;
		n.path             = path;
		n.polygon          = std::move(p);
		const Concavity2 c = measure_concavity(n.polygon);
		n.concavity        = c.max_concavity;
		n.notch_count      = c.notches;
		n.hole_count       = (int) n.polygon.holes.size();
		n.area             = area(n.polygon);
		if (c.max_vertex >= 0) n.notch = n.polygon.outer[c.max_vertex];
		D.nodes.push_back(std::move(n));
		measured.push_back(c);
		return (int) D.nodes.size() - 1;
	}

	// Which hole, if any: holes first (the paper), or when a hole is deeper than every notch, or when
	// only holes are left.
	void choose_target(Cut2& c) const
	{
		const Polygon2&   P = D.nodes[c.id].polygon;
		const Concavity2& m = measured[c.id];
		if (keep || P.holes.empty()) return;
		c.hole = (int) (std::max_element(m.hole_depth.begin(), m.hole_depth.end()) - m.hole_depth.begin());
		if (opt.hole_order == HoleOrder::ByConcavity && m.hole_depth[c.hole] <= m.max_concavity && m.max_concavity > opt.tau)
			c.hole = -1;
	}

	// Through the hole's centre: the paper's principal axis first, the minor axis, then a fan.
	void hole_lines(Cut2& c) const
	{
		Vec2            centre;
		Eigen::Matrix2d axes;
		hole_axes(D.nodes[c.id].polygon.holes[c.hole], centre, axes);
		c.cands.push_back({centre, axes.col(0), -1});
		c.cands.push_back({centre, axes.col(1), -1});
		for (int k = 1; k < 8; ++k)
			if (k != 4) c.cands.push_back({centre, Eigen::Rotation2Dd(M_PI * k / 8) * axes.col(0), -1});
		c.first_fit = opt.hole_handling != HoleCut::BestLine;
	}

	// The bisector of the notch's incident edge normals, pointing into the polygon (Algorithm 5.1's
	// cut line); it lies between u1 and u2, the directions that resolve the notch. With Best also
	// the cone between them, its own edges (a cut continuing an edge can reach the next notch in
	// line) and the directions towards the nearest notches inside it (cutting two at once).
	void notch_lines(Cut2& c) const
	{
		const Polygon2&   P = D.nodes[c.id].polygon;
		const Concavity2& m = measured[c.id];
		const int         n = (int) P.outer.size(), r = m.max_vertex;
		const Vec2 prev = P.outer[(r + n - 1) % n], cur = P.outer[r], next = P.outer[(r + 1) % n];
		const Vec2 u1 = (cur - prev).normalized(), u2 = (cur - next).normalized();   // edges extended past r
		Vec2       bis = u1 + u2;
		if (bis.norm() < 1e-12) bis = Vec2(-u1.y(), u1.x());
		c.cands.push_back({cur, bis.normalized(), r});
		c.first_fit = opt.cut_line_selection == CutLineSelection::Bisector;
		if (c.first_fit) return;
		const double span = std::atan2(cross(u1, u2), u1.dot(u2));   // from u1 to u2
		const int    k_max = std::max(2, opt.candidate_lines);
		for (int k = 0; k <= k_max + 1; ++k) c.cands.push_back({cur, Eigen::Rotation2Dd(span * k / (k_max + 1)) * u1, r});
		std::vector<std::pair<double, int>> near;
		for (int v = 0; v < n; ++v)
			if (v != r && m.outer[v] > opt.tau) near.push_back({(P.outer[v] - cur).norm(), v});
		std::sort(near.begin(), near.end());
		for (size_t i = 0; i < near.size() && i < 6; ++i) {
			const Vec2   d   = (P.outer[near[i].second] - cur).normalized();
			const double a   = std::atan2(cross(u1, d), u1.dot(d));
			const double tol = 1e-9;
			if ((span > 0 && a > -tol && a < span + tol) || (span < 0 && a < tol && a > span - tol)) c.cands.push_back({cur, d, r});
		}
	}

	// Split by candidate i; unless first-fit, score the pieces (notches, and holes by their depth).
	void trial(Cut2& c, size_t i) const
	{
		const Polygon2& P  = D.nodes[c.id].polygon;
		Trial2&         t  = c.trials[i];
		if (!separate(P, c.cands[i].from, c.cands[i].vertex, c.cands[i].dir, t.parts, &t.a, &t.b)) return;
		const double a0 = D.nodes[c.id].area;
		if (area(t.parts[0]) < 1e-9 * a0 || area(t.parts[1]) < 1e-9 * a0) return;
		const int holes_after = (int) (t.parts[0].holes.size() + t.parts[1].holes.size());
		if (c.hole >= 0 && holes_after >= (int) P.holes.size()) return;   // missed the hole
		t.crosses = keep && holes_after < (int) P.holes.size();
		t.ok      = true;
		if (c.first_fit) return;
		const Scored x = score(t.parts[0], keep), y = score(t.parts[1], keep);
		t.score = std::max(x.conc, y.conc);
		t.sum   = x.conc + y.conc;
	}

	void try_lines(Cut2& c) const
	{
		c.trials.assign(c.cands.size(), Trial2());
		if (!c.first_fit) {
			parallel_for(c.cands.size(), [&](size_t i) { trial(c, i); });
			return;
		}
		for (size_t i = 0; i < c.cands.size(); ++i) {
			trial(c, i);
			if (c.trials[i].ok && !c.trials[i].crosses) break;
		}
	}

	// The least concave pieces (ties by the total). As in 3D, the paper's bisector stands unless
	// another direction is clearly (10%) better; here also when it leaves the same worst concavity
	// but clearly less in total (a cut resolving two notches at once, as across a comb's tooth).
	void pick_line(Cut2& c) const
	{
		const double hair = 1e-9;
		const auto&  T    = c.trials;
		int          pick = -1;
		for (const bool allow_crossing : {false, true}) {
			for (int i = 0; i < (int) T.size(); ++i) {
				const Trial2& t = T[i];
				if (!t.ok || (t.crosses && !allow_crossing)) continue;
				if (pick < 0 || t.score < T[pick].score - hair || (t.score <= T[pick].score + hair && t.sum < T[pick].sum - hair))
					pick = i;
			}
			if (pick >= 0) break;
		}
		if (c.hole < 0 && pick > 0 && T[0].ok && !T[0].crosses) {
			const Trial2 &b = T[0], &t = T[pick];
			const bool better = t.score < 0.9 * b.score || (t.score <= b.score + hair && t.sum < 0.9 * b.sum);
			if (!better) pick = 0;
		}
		c.pick = pick;
	}

	int accept(Cut2& c)
	{
		const int id = c.id;
		if (c.pick < 0) {
			D.nodes[id].uncut = true;
			return 0;
		}
		Trial2& t = c.trials[c.pick];
		Node2&  nd = D.nodes[id];
		nd.has_cut  = true;
		nd.cut_from = t.a;
		nd.cut_to   = t.b;
		nd.line     = line_through(t.a, t.b - t.a);
		nd.hole_cut = c.hole >= 0;
		D.hole_cuts += c.hole >= 0;
		const std::string path = nd.path;
		for (int s = 0; s < 2; ++s) {
			const int ch         = add_node(std::move(t.parts[s]), id, path + char('0' + s));
			D.nodes[id].child[s] = ch;
			rec.push(ch);
		}
		return 1;
	}

	// Greedy cuts peel a comb's teeth one per level: deeper trees than in 3D are normal.
	static constexpr size_t kMaxDepth = 200;
};

} // namespace

Decomposition2 decompose(const Polygon2& polygon, const PolygonOptions& opt)
{
	if (!(opt.tau > 0) || !std::isfinite(opt.tau))
		throw Error(Error::InvalidOption, "tau must be a positive, finite length.");
	if (opt.max_parts < 0) throw Error(Error::InvalidOption, "max_parts must be 0 (unbounded) or positive.");
	// Centred, unit-size coordinates (as in 3D), mapped back at the end.
	Vec2 c = Vec2::Zero();
	for (const Vec2& p : polygon.outer) c += p;
	c /= (double) polygon.outer.size();
	const double s = extent2(polygon.outer);
	auto         to_unit = [&](Loop2 l) {
        for (Vec2& p : l) p = (p - c) / s;
        return l;
	};
	Polygon2 unit{to_unit(polygon.outer), {}};
	for (const Loop2& h : polygon.holes) unit.holes.push_back(to_unit(h));
	PolygonOptions o = opt;
	o.tau /= s;
	Decomposition2 D = Driver2(o).run(unit);
	D.tau = opt.tau;
	auto back = [&](Vec2& p) { p = p * s + c; };
	for (Node2& n : D.nodes) {
		for (Vec2& p : n.polygon.outer) back(p);
		for (Loop2& h : n.polygon.holes)
			for (Vec2& p : h) back(p);
		n.concavity *= s;
		n.area *= s * s;
		back(n.notch);
		back(n.cut_from);
		back(n.cut_to);
		n.line.d = n.line.d * s + n.line.n.dot(c);
	}
	return D;
}

} // namespace acd
