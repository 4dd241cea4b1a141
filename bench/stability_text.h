// SPDX-License-Identifier: MIT
// The prose of docs/stability.md: how each case is built, its ground truth, and the
// explanation of every SmartCollision cell that does not pass.
#pragma once
#include <string>

namespace stab {

extern const char* const kIntro;
extern const char* const kFooter;

/// Two sentences: how the case is built and what the ground truth is.
std::string rowDescription(const std::string& row);

/// Why a SmartCollision cell of `row` / `column` ends in `outcome`.
std::string explanation(const std::string& row, const std::string& column, const std::string& outcome);

}  // namespace stab
