// SPDX-License-Identifier: MIT
// Pair-level collision: minimum distance when apart, dynamic penetration depth
// (TPDV/RPDV) when penetrating, between two groups of placed models. This is what
// the scene runs per listed pair, and what the Bullet plugin runs per body pair.
// It needs the groups (group.h) and the pair settings (pair_settings.h) only.
//
// Threads: a PairTracker is used by one thread at a time; distinct trackers may run
// at once on distinct threads, over shared models (models and pieces are immutable).
#pragma once

#include <memory>
#include <vector>

#include "smartcollision/group.h"
#include "smartcollision/pair_settings.h"

namespace sc {

namespace detail {
struct PairState;
}

/// What one direction's update found.
enum class DirectionStatus {
  NotComputed,            ///< code InvalidArgument (settings out of range), or NoResult for
                          ///< a direction not updated (a scene's static or passive target)
  BeyondMaxDistance,      ///< code NoResult: apart by more than PairSettings::max_distance
  FirstSeenIntersecting,  ///< code InvalidInitialTransformation: no free pose known yet
  Separated,              ///< apart by more than the tolerance (distance > tolerance)
  Touching,               ///< apart or in contact within the tolerance; no depth (tpdv = 0)
  Penetrating,            ///< a depth: the proxy settled at the contact configuration
  Lagging,                ///< a depth, but the proxy ran out of iterations or of travel
                          ///< (PairSettings::proxy_travel_ratio) on its way: the contact
                          ///< configuration is not settled (catches up later)
};

/// One direction of a pair: target T, opponent O. All vectors in world coordinates.
/// Fields other than the ids are valid only when code == Ok.
struct DirectedResult {
  /// Ok, NoResult, InvalidInitialTransformation, or InvalidArgument (PairTracker
  /// only: settings out of range, nothing computed).
  ErrorCode code = ErrorCode::NoResult;
  /// What happened, in more detail than `code`: touching and penetrating are told
  /// apart (both can have distance 0), and a lagging proxy from a settled one.
  DirectionStatus status = DirectionStatus::NotComputed;
  int target_object = -1;    ///< Part::id of T's part in the reported contact
  int opponent_object = -1;  ///< Part::id of O's part
  int target_piece = -1;     ///< piece index within that part's model
  int opponent_piece = -1;
  /// > 0: separated, the minimum distance. <= 0: penetrating, -|tpdv|.
  double distance = 0.0;
  /// Unit; from O towards T: moving T along it increases separation.
  Vec3 normal = Vec3::UnitX();
  /// Closest points when separated; contact points with T at its contact pose otherwise.
  Vec3 point_on_target = Vec3::Zero();
  Vec3 point_on_opponent = Vec3::Zero();
  Feature target_feature;
  Feature opponent_feature;
  Vec3 tpdv = Vec3::Zero();  ///< current centre of T minus contact centre; 0 when apart
  Vec3 rpdv = Vec3::Zero();  ///< rotation vector: R(current) = Rot(rpdv) R(contact)
  Vec3 contact_position = Vec3::Zero();  ///< T's world centre of rotation at contact
  Quat contact_orientation = Quat::Identity();  ///< T's orientation at contact

  /// Distance <= 0 (a touching pair reads as penetrating here; `status` tells them
  /// apart: hasDepth()).
  bool penetrating() const { return code == ErrorCode::Ok && distance <= 0.0; }
  /// A translational or rotational depth is reported (Penetrating or Lagging).
  bool hasDepth() const {
    return status == DirectionStatus::Penetrating || status == DirectionStatus::Lagging;
  }
};

/// One contact of a direction (extension, for multi-point consumers such as
/// Bullet's manifolds): a leaf pair within the threshold at the contact configuration,
/// its target point carried to the target's current pose. World coordinates.
struct ContactPoint {
  Vec3 point_on_target = Vec3::Zero();    ///< on T at its current pose
  Vec3 point_on_opponent = Vec3::Zero();
  Vec3 normal = Vec3::UnitX();            ///< unit, from O towards T
  double separation = 0.0;                ///< along normal at the current pose; < 0 penetrating
  int target_object = -1;
  int opponent_object = -1;
  int target_piece = -1;
  int opponent_piece = -1;
};

/// Which directions to compute: [0] with group a as target, [1] with b as target.
struct Directions {
  bool a_target = true;
  bool b_target = true;
};

/// State of one unordered group pair across frames: per direction, the proxy of the
/// dynamic penetration depth (the last non-penetrating configuration of the target)
/// and the warm-start caches of the distance queries.
class SC_API PairTracker {
 public:
  PairTracker();
  ~PairTracker();
  PairTracker(PairTracker&&) noexcept;
  PairTracker& operator=(PairTracker&&) noexcept;

  /// Computes the requested directions. `out[0]` has a as target, `out[1]` has b.
  /// A direction not requested is left NoResult and its state is kept.
  /// A direction whose pair overlaps by more than the tolerance and that has no
  /// tracking state yet reports InvalidInitialTransformation; tracking starts once it
  /// is seen apart. One first seen touching, or overlapping by at most the tolerance,
  /// reports Touching (distance 0) and starts tracking (docs/penetration.md).
  /// Settings or a group failing validate() make every requested direction
  /// InvalidArgument and change no state (validate() gives the reason). A group's
  /// quaternion is normalised as the scene's are. Each direction follows a path from its last
  /// update (see Scene::setGroupPlacement); reset() first for a teleport. Allocates only while the
  /// pair's working sets grow.
  void update(const GroupView& a, const GroupView& b, Directions directions,
              const PairSettings& settings, DirectedResult out[2]);

  /// Every contact of direction 0 or 1 of the last update: leaf pairs within
  /// `threshold` (>= 0) of each other at the reported contact configuration (the
  /// closest points when apart), nearest first, one point per leaf pair; empty when
  /// the direction reported no Ok result. A pair in contact (a depth, or Touching at
  /// distance 0) is measured with the target lifted off by half the tolerance: leaf
  /// pairs still overlapping by more than that (a lagging proxy, a first sight that
  /// deep) are left out. Call it after update(), before the groups' parts change.
  void contactPoints(int direction, double threshold, std::vector<ContactPoint>& out);

  /// Drops the tracking state of direction 0 (a target) or 1 (b target).
  void forget(int direction);
  /// Drops the tracking state of both directions: the next update measures the pair
  /// as first seen. Call it when a group teleports (jumps without a path).
  void reset();
  /// True when the direction has seen the pair apart and follows it.
  bool tracking(int direction) const;

 private:
  std::unique_ptr<detail::PairState> state_;
};

}  // namespace sc
