// SPDX-License-Identifier: MIT
// Every tunable of a scene, its default, unit and meaning, in one place: the pair
// settings each pair's update receives (pair_settings.h), and how the scene finds
// and runs its pairs.
#pragma once

#include "smartcollision/pair_settings.h"

namespace sc {

/// Largest SceneSettings::threads accepted; 0 (automatic) uses at most kMaxAutoThreads.
inline constexpr int kMaxThreads = 256;
inline constexpr int kMaxAutoThreads = 8;

/// How a scene finds the group pairs within the maximum distance. Both list the same
/// pairs with the same results; BruteForce tests every pair (a reference, and a
/// baseline for benchmarks).
enum class Broadphase { Tree, BruteForce };

/// The pair settings (passed as they are to every pair's update) and the scene's own.
struct SceneSettings : PairSettings {
  /// Threads evaluating the listed pairs, the caller's included (0 = automatic: the
  /// hardware's, at most kMaxAutoThreads; 1 = serial). Results are the same, bit for
  /// bit and in the same order, for any count.
  int threads = 0;
  Broadphase broadphase = Broadphase::Tree;
  /// The scene also lists every contact within the tolerance of each result
  /// (PairStatus::contacts), for multi-point consumers. Off by default: it costs a
  /// second traversal per direction.
  bool contact_points = false;
};

/// Ok, or InvalidArgument naming the first field out of range (the pair settings'
/// first, then the scene's).
SC_API Status validate(const SceneSettings& settings);

}  // namespace sc
