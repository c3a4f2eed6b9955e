#include "acd/decompose3/measure_memo.h"
#include "acd/mesh/content_hash.h"

namespace acd {

MeasuredPtr MeasureMemo::find_or_make(const TriMesh& m, double tau, bool keep_cavities, const std::function<MeasuredPtr()>& make)
{
	const double        options[2] = {tau, keep_cavities ? 1.0 : 0.0};
	const std::uint64_t key        = mix(content_hash(m), options, sizeof options);
	const size_t        n          = m.F.size();
	return kept.find_or_make(
	    key, make,
	    [&] {   // kept while the budget allows
		    if (faces + n > max_faces) return false;
		    faces += n;
		    return true;
	    },
	    [&] { faces -= n; });
}

} // namespace acd
