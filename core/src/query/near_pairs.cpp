// SPDX-License-Identifier: MIT
#include "query/near_pairs.h"

#include <algorithm>
#include <cmath>

namespace sc::detail {

double TargetSphere::displacement(const Rigid& from, const Rigid& to) const {
  // A target point p = c + q (|q| <= radius) moves by at most
  // |(X - K) c| + ||R_X - R_K|| radius; the Frobenius norm bounds the spectral one.
  const double centre_shift = (to * center - from * center).norm();
  const double spin = (to.rotation - from.rotation).norm();
  return centre_shift + spin * radius;
}

double TargetSphere::motion(const Rigid& from, const Rigid& to) const {
  const double centre_shift = (to * center - from * center).norm();
  return centre_shift + (to.rotation - from.rotation).norm() * radius / std::sqrt(2.0);
}

const std::vector<LeafContact>* NearPairs::memo(const Rigid& o_from_t, double threshold) const {
  const bool same = valid_ && memo_valid_ && threshold == memo_threshold_ &&
                    o_from_t.rotation == memo_pose_.rotation &&
                    o_from_t.translation == memo_pose_.translation;
  return same ? &memo_out_ : nullptr;
}

void NearPairs::remember(const Rigid& o_from_t, double threshold,
                         const std::vector<LeafContact>& out) {
  memo_valid_ = true;
  memo_pose_ = o_from_t;
  memo_threshold_ = threshold;
  memo_out_ = out;
}

void NearPairs::install(const Rigid& pose, double reach) {
  valid_ = true;
  pose_ = pose;
  reach_ = reach;
  poses_.assign(1, pose);
  caches_.clear();
  gaps_.clear();
}

void NearPairs::keep(const SimplexCache& cache, const Vec3& center, double radius, double gap) {
  caches_.push_back(cache);
  gaps_.push_back({center, radius, gap, 0});
}

void NearPairs::indexPairs() {
  index_.clear();
  for (std::size_t i = 0; i < pairs_.size(); ++i)
    index_.push_back({{pairs_[i].t_leaf, pairs_[i].o_leaf}, static_cast<int>(i)});
  std::sort(index_.begin(), index_.end());
}

int NearPairs::find(const LeafPair& p) const {
  const auto it = std::lower_bound(index_.begin(), index_.end(), p,
                                   [](const auto& e, const LeafPair& k) { return e.first < k; });
  return it != index_.end() && it->first == p ? it->second : -1;
}

double NearPairs::gapBoundAt(std::size_t i, const Rigid& pose) const {
  const Gap& g = gaps_[i];
  const Rigid& from = poses_[static_cast<std::size_t>(g.pose)];
  const Mat3 rotation = pose.rotation - from.rotation;
  const Vec3 shift = rotation * g.center + (pose.translation - from.translation);
  return g.gap - (shift.norm() + rotation.norm() * g.radius);
}

void NearPairs::finishPending() {
  expected_work_ = pending_.work;
  pending_.active = false;
  pairs_.swap(pending_.found);
}

int NearPairs::pendingBudget(const Rigid& o_from_t, double threshold) const {
  // Node pairs per call: a rebuild of a broad contact (thousands of leaf pairs) spread
  // over a few physics steps, each of which calls this several times...
  const int base = std::max(64, expected_work_ / 8);
  // ...unless the kept pairs stop covering the target first. Pace the rest by the
  // calls left at the last call's speed. A body approaching a broad contact finds
  // many more pairs than the last rebuild did (11 node pairs, then 1,882, then 4,487
  // as a bunny meets a floor): past half the expected work, as much again is assumed
  // to remain.
  const double step = sphere_.displacement(pending_.last_pose, o_from_t);
  if (!(step > 0.0)) return base;
  // Kept pairs exist here: with none, every call is due and finishes the rebuild,
  // unless it runs ahead of a first contact (rebuildNearAhead): then a share per call,
  // paced by the gap left to the surface (at a base share, a rebuild restarted on the
  // way in was mostly left to the first contact's call), and a rebuild overtaken by
  // the motion leaves its work as the next one's front.
  const double covered = coveredReach(o_from_t) - threshold;
  if (pending_.receding && !(covered > 0.0)) return base;
  const double room = std::max(covered, pending_.approach);
  if (!(room > 0.0)) return base;
  const double calls_left = std::max(1.0, std::floor(room / step));
  const int rest = std::max(expected_work_ - pending_.work, pending_.work);
  return std::max(base, static_cast<int>(std::ceil(rest / calls_left)));
}

int NearPairs::prepareBounds(const Rigid& o_from_t) {
  // A pair's gap shrinks by at most its target leaf's displacement since its gap was
  // measured. Poses are kept while few; past that every gap is re-based on this pose
  // (a valid, looser bound) so the list stays short.
  constexpr std::size_t kMaxPoses = 32;
  auto changeTo = [&](const Rigid& from) {
    PoseChange d{o_from_t.rotation - from.rotation, o_from_t.translation - from.translation, 0.0};
    d.spin = d.rotation.norm();
    return d;
  };
  changes_.clear();
  for (const Rigid& from : poses_) changes_.push_back(changeTo(from));
  if (poses_.size() >= kMaxPoses) {
    for (std::size_t i = 0; i < gaps_.size(); ++i) {
      gaps_[i].gap = gapBound(i);
      gaps_[i].pose = 0;
    }
    poses_.clear();
    changes_.clear();
  }
  poses_.push_back(o_from_t);
  changes_.push_back(changeTo(o_from_t));
  return static_cast<int>(poses_.size()) - 1;
}

double NearPairs::gapBound(std::size_t i) const {
  const Gap& g = gaps_[i];
  const PoseChange& d = changes_[g.pose];
  return g.gap - ((d.rotation * g.center + d.translation).norm() + d.spin * g.radius);
}

}  // namespace sc::detail
