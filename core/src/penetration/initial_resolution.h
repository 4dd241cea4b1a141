// SPDX-License-Identifier: MIT
// A free pose near a pose where the pair already intersects (extension: resolve a pair
// first seen intersecting instead of reporting InvalidInitialTransformation).
#pragma once

#include <vector>

#include "query/convex_pair.h"
#include "query/group_pair_query.h"
#include "smartcollision/pair_settings.h"

namespace sc::detail {

/// Work arrays kept between calls.
struct ResolutionScratch {
  std::vector<LeafContact> contacts;
  std::vector<Vec3> normals;    ///< one row per intersecting leaf pair met so far
  std::vector<double> offsets;  ///< row: normal . t >= offset, t the total translation
  ConvexPairCache depth;        ///< the leaf pairs' EPA work arrays
};

/// Outline: the intersecting leaf pairs at `goal` each give a global exit (EPA on the
/// two convex leaves, convexDepth: direction n, depth d), a half-space n . t >= d + skin on the
/// target's translation t. The smallest t satisfying every half-space met so far is
/// tried; pairs it brings into intersection add their own half-spaces. Translation
/// only: the orientation is the input's, as in Input mode. Unbounded, when 8 rounds
/// or 2048 half-spaces free nothing (a deep non-convex overlap, whose leaves' exits
/// conflict), the target is swept in from beyond the opponent along 64 directions and
/// the best one's tilts (translationToi to the first contact): the shortest such exit.
/// @return true with `free_pose` = goal translated by t, a pose where no leaf pair
///   intersects; false when a bounded call finds no free pose within 32 rounds, or as
///   soon as an exit deeper than `max_depth` is met (a pose beyond touching, when the
///   caller only accepts one within the tolerance of it). `first`: an intersecting leaf
///   pair at `goal` already known, measured first (a deep one settles a bounded call
///   before every intersecting pair is gathered).
bool resolveInitialIntersection(GroupPairQuery& query, const Rigid& goal,
                                const PairSettings& settings, Rigid& free_pose,
                                ResolutionScratch& scratch, double max_depth = kInfinity,
                                const LeafContact* first = nullptr);

}  // namespace sc::detail
