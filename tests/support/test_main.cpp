// SPDX-License-Identifier: MIT
// GoogleTest main for every suite: traps invalid operations and division by zero,
// so a NaN or an unintended infinity fails the test where it is born.
#include <fenv.h>
#include <gtest/gtest.h>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  feenableexcept(FE_INVALID | FE_DIVBYZERO);
  return RUN_ALL_TESTS();
}
