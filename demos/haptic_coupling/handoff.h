// SPDX-License-Identifier: MIT
// What the haptic, physics and graphics loops hand each other: the device pose and
// the tool's state, as fixed arrays of doubles behind seqlocks (lock-free for the
// readers and the single writer).
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>

#include "smartcollision/bullet/bullet.h"
#include "smartcollision/haptics/virtual_coupling.h"

namespace sc::demo::haptic {

/// Single writer, any number of readers; N doubles, every word atomic (no data race).
template <std::size_t N>
class SeqLock {
 public:
  void write(const std::array<double, N>& v) {
    const unsigned s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_release);
    for (std::size_t i = 0; i < N; ++i) data_[i].store(v[i], std::memory_order_relaxed);
    seq_.store(s + 2, std::memory_order_release);
  }
  /// False until the first write, and when the writer was mid-write for every one of
  /// a few attempts (preempted there: a reader that spun would wait for it, and a
  /// FIFO haptic thread could wait on its own core); `out` is then left as it was.
  bool read(std::array<double, N>& out) const {
    std::array<double, N> copy;
    for (int attempt = 0; attempt < 64; ++attempt) {
      const unsigned s0 = seq_.load(std::memory_order_acquire);
      if (s0 == 0) return false;
      if (s0 & 1u) continue;
      for (std::size_t i = 0; i < N; ++i) copy[i] = data_[i].load(std::memory_order_relaxed);
      std::atomic_thread_fence(std::memory_order_acquire);
      if (seq_.load(std::memory_order_relaxed) == s0) {
        out = copy;
        return true;
      }
    }
    return false;
  }

 private:
  std::atomic<unsigned> seq_{0};
  std::array<std::atomic<double>, N> data_{};
};

using PoseWords = std::array<double, 7>;    // x y z qw qx qy qz
using StateWords = std::array<double, 15>;  // pose, v, w, physics step count, in contact

inline PoseWords wordsOf(const sc::haptics::CouplingPose& p) {
  return {p.position.x(),    p.position.y(),    p.position.z(),   p.orientation.w(),
          p.orientation.x(), p.orientation.y(), p.orientation.z()};
}

inline sc::haptics::CouplingPose poseOf(const double* w) {
  sc::haptics::CouplingPose p;
  p.position = Vec3(w[0], w[1], w[2]);
  p.orientation = Quat(w[3], w[4], w[5], w[6]).normalized();
  return p;
}

inline StateWords wordsOf(const sc::haptics::BodyState& s) {
  StateWords w{};
  const PoseWords p = wordsOf(s.pose);
  std::copy(p.begin(), p.end(), w.begin());
  for (int k = 0; k < 3; ++k) {
    w[std::size_t(7 + k)] = s.linear_velocity[k];
    w[std::size_t(10 + k)] = s.angular_velocity[k];
  }
  return w;
}

inline sc::haptics::BodyState stateOf(const StateWords& w) {
  sc::haptics::BodyState s;
  s.pose = poseOf(w.data());
  s.linear_velocity = Vec3(w[7], w[8], w[9]);
  s.angular_velocity = Vec3(w[10], w[11], w[12]);
  return s;
}

}  // namespace sc::demo::haptic
