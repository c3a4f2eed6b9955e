// A minimal parallel loop over one pool of std::threads (no TBB or OpenMP dependency for hosts to match),
// within a thread budget: a decomposition runs on the threads its caller grants (ThreadLimit), and the
// loops it nests share them instead of multiplying them.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <map>
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

// One pool of threads for the process, created on first use and kept: a loop borrows as many of them as
// its budget grants, and the thread that runs the loop works on it too. A borrowed thread that starts a
// loop of its own offers it to idle threads the same way, so nested loops share the pool instead of
// creating threads, and a loop never waits for a thread that is not already working on it (no deadlock
// however deep the nesting).
class ThreadPool
{
public:
	struct Job
	{
		std::function<void()> work;        // takes iterations until none is left
		unsigned              wanted = 0;  // helpers it may still take on
		unsigned              running = 0; // helpers working on it now
		std::condition_variable done;
	};

	static ThreadPool& instance()
	{
		static ThreadPool pool(std::max(1u, std::thread::hardware_concurrency()) - 1);
		return pool;
	}
	~ThreadPool()
	{
		{
			std::lock_guard<std::mutex> lock(mutex_);
			stop_ = true;
		}
		wake_.notify_all();
		for (std::thread& t : threads_) t.join();
	}
	// Runs job.work on the calling thread and on up to job.wanted idle pool threads; returns when all are done.
	void run(Job& job)
	{
		if (job.wanted > 0 && !threads_.empty()) {
			std::lock_guard<std::mutex> lock(mutex_);
			queue_.push_back(&job);
		}
		wake_.notify_all();
		job.work();
		std::unique_lock<std::mutex> lock(mutex_);
		queue_.erase(std::remove(queue_.begin(), queue_.end(), &job), queue_.end());   // no helper joins now
		job.done.wait(lock, [&] { return job.running == 0; });
	}

	// Works on queued loops on this thread until ready() holds: a thread waiting for what another is
	// making (a shared measure) lends itself to that work's loops instead of idling.
	template <class Ready>
	void help_until(Ready ready)
	{
		std::unique_lock<std::mutex> lock(mutex_);
		while (!ready()) {
			if (queue_.empty()) {   // nothing to take: look again shortly (ready() has no signal of its own)
				wake_.wait_for(lock, std::chrono::microseconds(200));
				continue;
			}
			work_on_front(lock);
		}
	}

private:
	explicit ThreadPool(unsigned n)
	{
		for (unsigned i = 0; i < n; ++i) threads_.emplace_back([this] { serve(); });
	}
	// Joins the queue's first loop as one more helper (the lock held on entry and on return).
	void work_on_front(std::unique_lock<std::mutex>& lock)
	{
		Job* job = queue_.front();
		if (--job->wanted == 0) queue_.pop_front();
		++job->running;
		lock.unlock();
		job->work();
		lock.lock();
		if (--job->running == 0) job->done.notify_all();
	}
	void serve()
	{
		std::unique_lock<std::mutex> lock(mutex_);
		for (;;) {
			wake_.wait(lock, [&] { return stop_ || !queue_.empty(); });
			if (stop_) return;
			work_on_front(lock);
		}
	}
	std::mutex               mutex_;
	std::condition_variable  wake_;
	std::deque<Job*>         queue_;
	std::vector<std::thread> threads_;
	bool                     stop_ = false;
};

// The value of a future another thread is making, this thread working on queued loops meanwhile.
template <class T>
T wait_helping(const std::shared_future<T>& f)
{
	ThreadPool::instance().help_until([&] { return f.wait_for(std::chrono::seconds(0)) == std::future_status::ready; });
	return f.get();
}

// Values that several threads may ask for at once, each made once: a value another thread is making is
// waited for (wait_helping), not made again. A make() that throws keeps nothing.
template <class Key, class Value>
class SharedResults
{
public:
	// The value under `key`, else make()'s. When the key is new, claim() (under the lock) says whether
	// to keep it; release() (under the lock) undoes a claim whose make() threw.
	template <class Make, class Claim, class Release>
	Value find_or_make(const Key& key, const Make& make, const Claim& claim, const Release& release)
	{
		std::promise<Value> made;
		{
			std::unique_lock<std::mutex> lock(mutex_);
			const auto                   it = kept_.find(key);
			if (it != kept_.end()) {
				++hits_;
				const std::shared_future<Value> f = it->second;
				lock.unlock();
				return wait_helping(f);
			}
			if (!claim()) {
				lock.unlock();
				return make();
			}
			kept_.emplace(key, made.get_future().share());
		}
		try {
			Value v = make();   // outside the lock: makers run on all cores
			made.set_value(v);
			return v;
		}
		catch (...) {
			made.set_exception(std::current_exception());
			std::lock_guard<std::mutex> lock(mutex_);
			kept_.erase(key);
			release();
			throw;
		}
	}
	template <class Make>
	Value find_or_make(const Key& key, const Make& make)
	{
		return find_or_make(key, make, [] { return true; }, [] {});
	}
	size_t size() const
	{
		std::lock_guard<std::mutex> lock(mutex_);
		return kept_.size();
	}
	size_t hits() const { return hits_; }

private:
	mutable std::mutex                             mutex_;
	std::map<Key, std::shared_future<Value>>       kept_;
	std::atomic<size_t>                            hits_{0};
};

// Runs fn(0..n-1) on the budget's threads (the caller and pool threads); each of them passes on its share
// of the budget to the loops fn nests. The first exception is rethrown after all finish. Which thread runs
// which i never changes a result: fn(i) writes only what belongs to i.
template <class Fn>
void parallel_for(size_t n, Fn fn)
{
	const unsigned      budget  = available_threads();
	const size_t        workers = std::max<size_t>(1, std::min<size_t>(budget, n));
	const int           share   = (int) std::max<size_t>(1, budget / workers);
	std::atomic<size_t> next{0};
	std::exception_ptr  error;
	std::mutex          error_mutex;
	ThreadPool::Job     job;
	job.wanted = (unsigned) workers - 1;
	job.work   = [&] {
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
	if (workers == 1)
		job.work();
	else
		ThreadPool::instance().run(job);
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

// std::sort of [first, last) in two halves on two cores, then merged: the same order as one sort when
// `less` is a total order (no two elements equivalent), on any number of threads.
template <class It, class Less = std::less<>>
void sort_halves(It first, It last, Less less = Less())
{
	const It half = first + (last - first) / 2;
	parallel_for(2, [&](size_t k) { std::sort(k ? half : first, k ? last : half, less); });
	std::inplace_merge(first, half, last, less);
}

} // namespace acd
