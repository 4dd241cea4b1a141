// SPDX-License-Identifier: MIT
// Separating planes of node pairs' hulls, kept for the sweeps of a translation.
//
// GJK on a node pair leaves the closest points' normal n and the gap d: along n the
// hulls are d apart. Translating the target piece by v (its rotation unchanged)
// moves that separation to d + n.v, exactly, whatever the true distance does. So a
// plane found at one pose bounds the pair at every translate of it: a proxy's slide,
// whose sweeps all run at one rotation (and whose goal was just measured at it),
// prunes with the planes its earlier queries found instead of running GJK again.
// Bounded memory: a direct-mapped table, a pair's entry overwritten by another's.
#pragma once

#include <cstdint>
#include <vector>

#include "smartcollision/types.h"

namespace sc::detail {

class PlaneMemo {
 public:
  /// Separation of the pair, target piece at translation x: >= offset + normal.dot(x).
  struct Plane {
    Vec3 normal = Vec3::UnitX();
    double offset = 0.0;
  };
  static constexpr int kPlanes = 3;  ///< per pair: the latest ones
  /// 192 bytes each, allocated on the first sweep: a slide's sweeps run GJK on a few
  /// hundred node pairs.
  static constexpr std::size_t kEntries = 1024;

  /// Every plane forgotten (the groups' pieces or placements changed).
  void clear() {
    ++epoch_;
    if (epoch_ == 0) {  // wrapped: stale entries would look current
      entries_.assign(entries_.size(), Entry());
      epoch_ = 1;
    }
  }

  /// Records that the pair `key`'s hulls are `gap` apart along `normal`, the target
  /// piece placed by `piece` (rotation and translation).
  void record(std::uint64_t key, const Rigid& piece, const Vec3& normal, double gap) {
    if (entries_.empty()) entries_.resize(kEntries);
    Entry& e = entries_[slotOf(key)];
    if (e.key != key || e.epoch != epoch_ || e.rotation != piece.rotation) {
      e.key = key;
      e.epoch = epoch_;
      e.rotation = piece.rotation;
      e.count = 0;
      e.next = 0;
    }
    e.planes[e.next] = {normal, gap - normal.dot(piece.translation)};
    e.next = (e.next + 1) % kPlanes;
    if (e.count < kPlanes) ++e.count;
  }

  /// The planes of `key` valid at `rotation` (the target piece's), or none: their
  /// count, `planes` pointing at them.
  int find(std::uint64_t key, const Mat3& rotation, const Plane*& planes) const {
    if (entries_.empty()) return 0;
    const Entry& e = entries_[slotOf(key)];
    if (e.key != key || e.epoch != epoch_ || e.rotation != rotation) return 0;
    planes = e.planes;
    return e.count;
  }

 private:
  struct Entry {
    std::uint64_t key = ~std::uint64_t{0};
    std::uint32_t epoch = 0;
    int count = 0;
    int next = 0;
    Mat3 rotation = Mat3::Zero();
    Plane planes[kPlanes];
  };

  static std::size_t slotOf(std::uint64_t key) {
    // Fibonacci hashing, as PairCache.
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 32) & (kEntries - 1);
  }

  std::vector<Entry> entries_;
  std::uint32_t epoch_ = 1;
};

}  // namespace sc::detail
