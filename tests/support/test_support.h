// SPDX-License-Identifier: MIT
// Shared helpers for all test suites: seeded randomness, vector expectations,
// and a scoped guard for code that intends to produce infinities.
#pragma once

#include <fenv.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "smartcollision/types.h"

namespace sc::test {

/// Fixed-seed generator; the seed is printed by SCOPED_TRACE in property tests.
using Rng = std::mt19937_64;

inline double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

/// A property test's number of cases: `full`, or `sanitized` in the sanitizer builds
/// (which run an order of magnitude slower).
constexpr int caseCount(int full, int sanitized) { return SC_TEST_SANITIZED ? sanitized : full; }

/// Uniformly distributed unit quaternion (Shoemake).
Quat randomRotation(Rng& rng);
/// Unit vector uniform on the sphere.
Vec3 randomDirection(Rng& rng);

/// Disables FP traps for its lifetime (for code where inf is intended).
class FpTrapsOff {
 public:
  FpTrapsOff() : saved_(fegetexcept()) { fedisableexcept(FE_ALL_EXCEPT); }
  ~FpTrapsOff() {
    feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(saved_);
  }
  FpTrapsOff(const FpTrapsOff&) = delete;
  FpTrapsOff& operator=(const FpTrapsOff&) = delete;

 private:
  int saved_;
};

}  // namespace sc::test

#define EXPECT_VEC_NEAR(a, b, tol)                                         \
  do {                                                                     \
    const ::sc::Vec3 sc_a_ = (a);                                          \
    const ::sc::Vec3 sc_b_ = (b);                                          \
    EXPECT_LE((sc_a_ - sc_b_).norm(), (tol))                               \
        << "  " #a " = " << sc_a_.transpose() << "\n  " #b " = " << sc_b_.transpose(); \
  } while (0)
