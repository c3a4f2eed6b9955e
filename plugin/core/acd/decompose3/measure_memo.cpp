#include "acd/decompose3/measure_memo.h"
#include "acd/mesh/content_hash.h"

namespace acd {

MeasuredPtr MeasureMemo::find_or_make(const TriMesh& m, double tau, bool keep_cavities, const std::function<MeasuredPtr()>& make)
{
	const double        options[2] = {tau, keep_cavities ? 1.0 : 0.0};
	const std::uint64_t key        = mix(content_hash(m), options, sizeof options);
	{
		std::lock_guard<std::mutex> lock(mutex);
		const auto                  it = kept.find(key);
		if (it != kept.end()) {
			++hit;
			return it->second;
		}
	}
	MeasuredPtr ms = make();   // outside the lock: the trials measure on all cores
	std::lock_guard<std::mutex> lock(mutex);
	if (faces + m.F.size() <= max_faces && kept.emplace(key, ms).second) faces += m.F.size();
	return ms;
}

} // namespace acd
