// A minimal test harness: register cases with ACD_TEST, check with CHECK / CHECK_NEAR.
#pragma once

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace acdtest {
struct Case
{
	const char*           name;
	std::function<void()> fn;
};
std::vector<Case>& registry();
extern int failures;
struct Reg
{
	Reg(const char* n, std::function<void()> f) { registry().push_back({n, std::move(f)}); }
};
} // namespace acdtest

#define ACD_CAT2(a, b) a##b
#define ACD_CAT(a, b) ACD_CAT2(a, b)
#define ACD_TEST(name)                                                             \
	static void name();                                                            \
	static acdtest::Reg ACD_CAT(reg_, name)(#name, name);                          \
	static void name()
#define CHECK(cond)                                                                \
	do {                                                                           \
		if (!(cond)) {                                                             \
			std::printf("  FAILED %s:%d: %s\n", __FILE__, __LINE__, #cond);        \
			++acdtest::failures;                                                   \
		}                                                                          \
	} while (0)
#define CHECK_NEAR(a, b, tol)                                                      \
	do {                                                                           \
		double va_ = (a), vb_ = (b);                                               \
		if (!(std::abs(va_ - vb_) <= (tol))) {                                     \
			std::printf("  FAILED %s:%d: %s = %.12g vs %s = %.12g (tol %g)\n",      \
			            __FILE__, __LINE__, #a, va_, #b, vb_, (double) (tol));      \
			++acdtest::failures;                                                   \
		}                                                                          \
	} while (0)
