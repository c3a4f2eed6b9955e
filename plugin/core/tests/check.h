// The C++ tests run on doctest (Debian's doctest-dev); CHECK_NEAR compares within an absolute tolerance.
#pragma once

#include <doctest/doctest.h>

#include <cmath>

#define CHECK_NEAR(a, b, tol) CHECK(std::abs(double(a) - double(b)) <= double(tol))
