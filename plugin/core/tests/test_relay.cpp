#include "acd/decompose3/relay.h"

#include "check.h"

#include <algorithm>
#include <set>
#include <string>
#include <vector>

using namespace acd;

namespace {

// Two searches as decompose's thorough search runs them: the one on the calling thread ends at once
// (once the other has started, so that it is not left for the caller), the other reports `reports`
// times, a nested loop of `nested` short steps before each report. Records who reported what, and on
// which threads the nested steps ran.
struct TwoSearches
{
	std::vector<std::string>  heard;
	std::vector<int>          shares;
	std::set<std::thread::id> host_threads, nested_threads;
	std::mutex                nested_mutex;
	std::atomic<bool>         other_started{false}, other_stopped{false};

	void run(int reports, int nested, int cancel_after = -1)
	{
		const ThreadLimit                     two(2);
		const std::function<bool(int, const char*)> host = [&](int pct, const char* msg) {
			host_threads.insert(std::this_thread::get_id());
			heard.emplace_back(msg);
			shares.push_back(pct);
			return cancel_after < 0 || (int) heard.size() < cancel_after;
		};
		Relay relay(host);
		parallel_for(2, [&](size_t k) {
			{
				const ThreadLimit    both(2);   // each search may take every thread, as decompose's do
				const Relay::Running running(relay);
				const auto           report = relay.progress((int) k);
				if (std::this_thread::get_id() == main) {
					for (int wait = 0; wait < 2000 && !other_started; ++wait) std::this_thread::sleep_for(std::chrono::milliseconds(1));
					report(100, "first done");
				}
				else {
					other_started = true;
					for (int r = 0; r < reports; ++r) {
						parallel_for(nested, [&](size_t) {
							std::this_thread::sleep_for(std::chrono::microseconds(500));
							std::lock_guard<std::mutex> lock(nested_mutex);
							nested_threads.insert(std::this_thread::get_id());
						});
						if (!report(r % 2 ? 10 * r : 40, ("other " + std::to_string(r)).c_str())) {   // steps back
							other_stopped = true;
							break;
						}
					}
				}
			}
			relay.help_other();
		});
	}
	const std::thread::id main = std::this_thread::get_id();   // the calling thread
};

} // namespace

TEST_CASE("relay: the other search's reports reach the host on its thread after the first search ended, and "
          "the thread that ended first helps the other's loops")
{
	if (std::thread::hardware_concurrency() < 2) return;   // one thread runs both searches in turn
	TwoSearches t;
	t.run(6, 400);
	REQUIRE(t.other_started);
	CHECK(t.host_threads == std::set<std::thread::id>{t.main});   // only on the calling thread
	REQUIRE(!t.heard.empty());
	CHECK(t.heard.front() == "first done");
	CHECK(t.heard.back() == "other 5");   // the other's last report, heard after the first had ended
	CHECK(t.heard.size() >= 3);           // and more than its last: each 200 ms loop spans a relay
	CHECK(t.nested_threads.count(t.main) == 1);   // the caller took steps of the other's loops
	CHECK(std::is_sorted(t.shares.begin(), t.shares.end()));   // the host's bar never steps back
	CHECK(t.shares.front() == 50);   // the mean of the two searches' shares
}

TEST_CASE("relay: a cancel at the host stops the other search at its next report")
{
	if (std::thread::hardware_concurrency() < 2) return;
	TwoSearches t;
	t.run(50, 200, 2);   // the host says stop at its second report
	CHECK(t.other_stopped);
	CHECK(t.heard.size() == 2);
	CHECK(t.heard.back().rfind("other ", 0) == 0);
}
