// SPDX-License-Identifier: MIT
// The convex fast path of the initial-intersection resolution: a pair of single
// convex pieces (boxes, hulls, one-piece convex models) first seen intersecting gets
// its exact global depth from GJK and EPA on the two pieces, without the hierarchy
// traversal, the contact rows and the proxy steps of the general path.
#pragma once

#include "penetration/proxy_tracker.h"
#include "query/convex_pair.h"

namespace sc::detail {

/// True when both groups are one convex piece each (one leaf, the piece itself).
bool isConvexPair(const GroupPairQuery& query, const GroupView& target, const GroupView& opponent);

/// For a convex pair in a rotation mode that keeps the goal's orientation (Input,
/// None), intersecting at `goal`: `out` is the exact global depth there (TPDV along
/// the exit of least translation, RPDV 0) and `free_pose` the goal moved out along
/// that exit by the depth and half the tolerance, where the proxy starts.
/// @return false (nothing written) for any other pair or mode, or when the pair is
///   apart or only touches at `goal`: the general path handles those.
bool resolveConvexPair(const GroupPairQuery& query, const GroupView& target,
                       const GroupView& opponent, const Rigid& goal, const PairSettings& settings,
                       ConvexPairCache& cache, ProxyOutcome& out, Rigid& free_pose);

/// One update of a convex pair in Input or None mode, straight on the two pieces:
/// the general path's proxy steps (proxy_tracker.h) for a single leaf pair, with
/// GJK warm-started from `cache` and the pieces' support mappings, so no hierarchy,
/// no contact gathering and a QP of at most one row (a projection on a plane). The
/// proxy is `tracker`'s, read at the start and written back.
/// @return false (nothing written) for any other pair or mode, a pair first seen
///   intersecting, and None mode's first penetrating update (its impact pose): the
///   general path handles those.
bool trackConvexPair(const GroupPairQuery& query, const GroupView& target,
                     const GroupView& opponent, const Rigid& goal, const Vec3& center,
                     const PairSettings& settings, ConvexPairCache& cache, ProxyTracker& tracker,
                     ProxyOutcome& out);

}  // namespace sc::detail
