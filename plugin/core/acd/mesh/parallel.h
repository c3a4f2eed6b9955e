// A minimal parallel loop over std::thread (no TBB or OpenMP dependency for hosts to match).
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace acd {

// Runs fn(0..n-1) on the machine's cores; the first exception is rethrown after all finish.
template <class Fn>
void parallel_for(size_t n, Fn fn)
{
	const size_t             workers = std::max(1u, std::min<unsigned>(std::thread::hardware_concurrency(), (unsigned) n));
	std::atomic<size_t>      next{0};
	std::exception_ptr       error;
	std::mutex               error_mutex;
	std::vector<std::thread> pool;
	auto                     work = [&] {
        for (size_t i; (i = next++) < n;) {
            try {
                fn(i);
            }
            catch (...) {
                std::lock_guard<std::mutex> lock(error_mutex);
                if (!error) error = std::current_exception();
            }
        }
	};
	for (size_t w = 1; w < workers; ++w) pool.emplace_back(work);
	work();
	for (auto& t : pool) t.join();
	if (error) std::rethrow_exception(error);
}

} // namespace acd
