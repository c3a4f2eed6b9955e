#include "acd/mesh/parallel.h"
#include "check.h"

#include <random>
#include <utility>
#include <vector>

using namespace acd;

TEST_CASE("sort_halves: the order of one sort, on one thread and on every core, at any length")
{
	std::mt19937 rng(7);
	for (size_t n : {0, 1, 2, 3, 1000, 100001}) {
		std::vector<std::pair<int, int>> v(n);
		for (size_t i = 0; i < n; ++i) v[i] = {(int) (rng() % 50), (int) i};   // many equal keys, told apart by i
		std::vector<std::pair<int, int>> want = v;
		std::sort(want.begin(), want.end());
		for (int threads : {1, 0}) {
			const ThreadLimit limit(threads);
			std::vector<std::pair<int, int>> got = v;
			sort_halves(got.begin(), got.end());
			CHECK(got == want);
		}
		// With a comparison of its own: descending by key, then by position.
		std::vector<std::pair<int, int>> down = v;
		sort_halves(down.begin(), down.end(), std::greater<>());
		std::sort(want.begin(), want.end(), std::greater<>());
		CHECK(down == want);
	}
}
