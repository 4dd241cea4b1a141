// SPDX-License-Identifier: MIT
// Pair-level rows of the stability matrix: SmartCollision's PairTracker in each
// rotation mode against FCL, libccd and Bullet's GJK-EPA on the same boxes.
#pragma once
#include <vector>

#include "stability_common.h"

namespace stab {

/// Column names shared by the program's table.
inline constexpr const char* kTruth = "ground truth";
inline constexpr const char* kScInput = "SC core Input";
inline constexpr const char* kScCold = "SC core Input, cold start";
inline constexpr const char* kScMix = "SC core Mix";
inline constexpr const char* kScFree = "SC core Free";
inline constexpr const char* kScNone = "SC core None";
inline constexpr const char* kScPotential = "SC Bullet potential";
inline constexpr const char* kScManifold = "SC Bullet manifold";
inline constexpr const char* kFclDistance = "FCL signed distance";
inline constexpr const char* kFclCollide = "FCL collide";
inline constexpr const char* kCcdEpa = "libccd GJK-EPA";
inline constexpr const char* kCcdMpr = "libccd MPR";
inline constexpr const char* kBtGjkEpa = "Bullet GJK-EPA";
inline constexpr const char* kBtBox = "Bullet btBoxShape";
inline constexpr const char* kBtGImpact = "Bullet GImpact";

/// Every pair-level row (touching, degenerate simplices, deep and rotational
/// penetration), all columns; the dynamics columns are marked n/a.
std::vector<Cell> runPairRows();

}  // namespace stab
