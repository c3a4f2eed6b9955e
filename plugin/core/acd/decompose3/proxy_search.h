// The search on a proxy: a solid with many faces is decimated to a few thousand (mesh/decimate.h), the
// cuts and the merge are searched on that copy, and their planes then cut the solid itself, so the
// parts stay an exact partition of it. The certificate is the cuts' own, measured on every part of the
// solid (never on the proxy); a part that fails it is searched again on a finer proxy, and below the
// proxy size on the part itself. Merges found on the proxy are made on the solid only where the union
// of the original parts passes the certificate.
#pragma once

#include "acd/decompose3/decompose.h"

namespace acd {

struct ProxySettings
{
	int    above  = 30000;   // solids with more faces are searched on a proxy
	int    faces  = 20000;   // the first proxy's faces; each finer one has four times as many
	double error  = 0.125;   // decimation's error bar, a share of tau
	double widest = 0.25;    // a proxy farther from the solid than this share of tau is refined
	int    levels = 3;       // proxies tried before a part is searched as it is
};

class MergeMemo;
class MeasureMemo;

// The cut tree and (options.merge_parts) the merged parts of a solid centred and at unit size; on a
// proxy when it has more than settings.above faces and no max_parts bound, else on the solid. `memo`:
// unions an earlier search of the solid measured (merge.h); `measures`: the parts it measured
// (measure_memo.h).
Decomposition search(const Solid& solid, const DecomposeOptions& options, const ProxySettings& settings = {},
                     MergeMemo* memo = nullptr, MeasureMemo* measures = nullptr);

// Of two cut trees of one proxy, whether `a` is the better plan: the fewer parts once each part not
// within `tau` (the solid's) counts twice (on the solid it is certified, or searched again and cut at
// least once more), then fewer_parts(). A plan is not thrown away, as a final
// tree is, for one part a hair over tau on the proxy. (The proxy's trees are cut below tau and merged at
// it, so their own tau_convex() says little.)
bool better_plan(const Decomposition& a, const Decomposition& b, double tau);

} // namespace acd
