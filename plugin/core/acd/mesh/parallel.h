// A minimal parallel loop over std::thread (no TBB or OpenMP dependency for hosts to match), within a
// thread budget: a decomposition runs on the threads its caller grants (ThreadLimit), and the loops it
// nests share them instead of multiplying them.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace acd {

// The threads parallel_for may use on this thread (0: every core).
inline int& thread_budget()
{
	thread_local int budget = 0;
	return budget;
}

// Grants `threads` (0: every core) to the loops run on this thread while it lives.
class ThreadLimit
{
public:
	explicit ThreadLimit(int threads) : saved(thread_budget()) { thread_budget() = std::max(0, threads); }
	~ThreadLimit() { thread_budget() = saved; }
	ThreadLimit(const ThreadLimit&)            = delete;
	ThreadLimit& operator=(const ThreadLimit&) = delete;

private:
	int saved;
};

// How many threads the budget grants here.
inline unsigned available_threads()
{
	const int b = thread_budget();
	return b > 0 ? (unsigned) b : std::max(1u, std::thread::hardware_concurrency());
}

// Runs fn(0..n-1) on the budget's threads; each of them passes on its share of the budget to the loops
// fn nests. The first exception is rethrown after all finish. Which thread runs which i never changes
// a result: fn(i) writes only what belongs to i.
template <class Fn>
void parallel_for(size_t n, Fn fn)
{
	const unsigned           budget  = available_threads();
	const size_t             workers = std::max<size_t>(1, std::min<size_t>(budget, n));
	const int                share   = (int) std::max<size_t>(1, budget / workers);
	std::atomic<size_t>      next{0};
	std::exception_ptr       error;
	std::mutex               error_mutex;
	std::vector<std::thread> pool;
	auto                     work = [&] {
        ThreadLimit limit(share);
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

// parallel_for over 0..n-1 handed out `chunk` at a time: for many small fn(i), where taking one i at
// a time would cost more than fn itself.
template <class Fn>
void parallel_for_chunked(size_t n, size_t chunk, Fn fn)
{
	parallel_for((n + chunk - 1) / chunk, [&](size_t c) {
		for (size_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i) fn(i);
	});
}

} // namespace acd
