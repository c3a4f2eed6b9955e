#include "acd/decompose3/measure_memo.h"
#include "acd/mesh/content_hash.h"
#include "acd/mesh/parallel.h"

namespace acd {

MeasuredPtr MeasureMemo::find_or_make(const TriMesh& m, double tau, bool keep_cavities, const std::function<MeasuredPtr()>& make)
{
	const double              options[2] = {tau, keep_cavities ? 1.0 : 0.0};
	const std::uint64_t       key        = mix(content_hash(m), options, sizeof options);
	std::promise<MeasuredPtr> made;
	{
		std::unique_lock<std::mutex> lock(mutex);
		const auto                   it = kept.find(key);
		if (it != kept.end()) {   // kept, or being made on another thread: wait for it rather than make it twice
			++hit;
			const std::shared_future<MeasuredPtr> f = it->second;
			lock.unlock();
			return wait_helping(f);
		}
		if (faces + m.F.size() > max_faces) {
			lock.unlock();
			return make();
		}
		kept.emplace(key, made.get_future().share());
		faces += m.F.size();
	}
	try {
		MeasuredPtr ms = make();   // outside the lock: the trials measure on all cores
		made.set_value(ms);
		return ms;
	}
	catch (...) {
		made.set_exception(std::current_exception());
		std::lock_guard<std::mutex> lock(mutex);
		kept.erase(key);
		faces -= m.F.size();
		throw;
	}
}

} // namespace acd
