// Two searches run side by side (decompose.cpp's cut_search = thorough) and one host: their reports,
// each search's progress half of the whole, reach the host on the calling thread only (its callback may
// touch its GUI); a cancel there reaches both at their next report. When the search on the calling thread
// ends first, that thread lends itself to the other's loops (else the other runs on one thread fewer to
// its end) and passes the other's latest report on every 100 ms meanwhile. It holds no measure half made
// then, so the work it helps with never waits for it.
#pragma once

#include "acd/mesh/parallel.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace acd {

class Relay
{
public:
	explicit Relay(const std::function<bool(int, const char*)>& host) : host(host), caller(std::this_thread::get_id()) {}

	// Search k's callback (k = 0 or 1).
	std::function<bool(int, const char*)> progress(int k)
	{
		return [this, k](int p, const char* msg) {
			pct[k] = p;
			if (std::this_thread::get_id() == caller) pass(msg);
			else {
				std::lock_guard<std::mutex> lock(mutex);
				waiting = msg;
			}
			return !cancelled.load();
		};
	}

	// A search running while it lives.
	struct Running
	{
		Relay& r;
		explicit Running(Relay& r) : r(r) { ++r.running; }
		~Running() { --r.running; }
	};

	// After the caller's own search ended: until the other ends (none running: it ran before, or runs next
	// on this thread).
	void help_other()
	{
		if (std::this_thread::get_id() != caller) return;
		while (running > 0) {
			const auto next = std::chrono::steady_clock::now() + std::chrono::milliseconds(100);
			ThreadPool::instance().help_until([&] { return running == 0 || std::chrono::steady_clock::now() >= next; });
			std::string msg;
			{
				std::lock_guard<std::mutex> lock(mutex);
				msg.swap(waiting);
			}
			if (!msg.empty()) pass(msg.c_str());
		}
	}

private:
	// The mean of the two searches' shares, never below what the host was shown (each search's own
	// estimate can step back as its tree grows).
	void pass(const char* msg)
	{
		shown = std::max(shown, (pct[0] + pct[1]) / 2);
		if (host && !cancelled && !host(shown, msg)) cancelled = true;
	}

	const std::function<bool(int, const char*)>& host;
	const std::thread::id                        caller;
	std::atomic<int>                             pct[2] = {0, 0};
	std::atomic<int>                             running{0};
	int                                          shown = 0;   // the share last passed (the calling thread's)
	std::atomic<bool>                            cancelled{false};
	std::mutex                                   mutex;
	std::string                                  waiting;   // the other search's latest report
};

} // namespace acd
