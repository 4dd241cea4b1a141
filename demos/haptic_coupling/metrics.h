// SPDX-License-Identifier: MIT
// What the haptic and physics loops measure (rates, periods, force continuity,
// energy, non-finite values, memory) and its JSON report (docs/haptics.md).
#pragma once

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <string>
#include <vector>

#include "smartcollision/bullet/bullet.h"
#include "smartcollision/haptics/virtual_coupling.h"

namespace sc::demo::haptic {

/// Haptic periods in 1 us bins up to 50 ms (longer ones in the last bin), plus the
/// exact maximum: fixed memory, so that a soak's resident size does not grow with it.
class PeriodHistogram {
 public:
  void add(double seconds) {
    const double us = std::max(0.0, seconds * 1e6);
    ++bins_[std::min(bins_.size() - 1, std::size_t(us))];
    ++count_;
    max_ = std::max(max_, seconds);
  }
  long count() const { return count_; }
  double max() const { return max_; }
  /// The p-quantile [s], to the bin's centre (0.5 us).
  double percentile(double p) const;

 private:
  std::vector<long> bins_ = std::vector<long>(50000, 0);
  long count_ = 0;
  double max_ = 0.0;
};

bool finite(const sc::haptics::BodyState& s);
bool finite(const sc::haptics::CouplingWrench& w);
/// Kinetic energy of a body [J] (translation + rotation about its principal axes).
double kineticEnergy(const btRigidBody& b);

/// The loops' figures. Each is written by one thread (noted) and read after the
/// join, or as a display value.
struct LoopMetrics {
  std::atomic<long> haptic_count{0}, physics_count{0};
  double elapsed = 0.0;       ///< seconds of the run: simulated with --lockstep
  double wall_seconds = 0.0;  ///< wall time of the run
  bool lockstep = false;
  std::atomic<bool> haptic_fifo{false};  ///< the haptic thread got FIFO scheduling

  // Haptic thread.
  PeriodHistogram periods;
  int since_miss = 1 << 30;            ///< haptic samples since a loop missed its deadline
  Vec3 previous_force = Vec3::Zero();  ///< the last sample's reaction
  double previous_steps = 0.0;         ///< physics steps at the last sample
  bool previous_contact = false;       ///< the tool touched at the last sample
  int since_impact = 1 << 30;          ///< haptic samples since a contact's onset
  long impacts = 0;                    ///< contact onsets seen by the haptic loop
  double max_impact_jump = 0.0, max_impact_ratio = 0.0;
  long unchecked_samples = 0;
  double max_jump_any = 0.0, max_jump = 0.0, max_jump_ratio = 0.0, max_coupling_force = 0.0;
  long non_finite_samples = 0;  ///< samples with a non-finite body state or reaction

  // Physics thread.
  long non_finite_steps = 0;                       ///< steps with a non-finite body state or wrench
  long steps_over_period = 0;                      ///< steps that took longer than their period
  double max_kinetic = 0.0;                        ///< the tool's largest kinetic energy [J]
  long rss_after_1s_kb = 0, rss_after_60s_kb = 0;  ///< 0 when the run is shorter
  double step_seconds = 0.0, step_max = 0.0;
  std::atomic<double> max_depth{0.0}, generated{0.0};
  std::atomic<double> last_force{0.0};  ///< haptic thread, for the overlay
};

/// What the report needs beyond LoopMetrics: the run's set-up and its final state.
struct RunReport {
  std::string scene;
  const char* device = "";
  double haptic_dt = 0.0, physics_dt = 0.0, max_device_speed = 0.0;
  sc::haptics::CouplingGains gains;
  sc::haptics::PassivityReport passivity;
  const sc::haptics::CouplingEnergyMonitor* monitor = nullptr;
  std::size_t tool_triangles = 0, fixed_triangles = 0;
  sc::haptics::BodyState final_state;
  Vec3 final_rotation_vector = Vec3::Zero();  ///< in the tool's mesh frame
  double inserted_depth = 0.0;
  bool inside = false;
};

/// The JSON metrics of a finished run.
std::string metricsJson(const LoopMetrics& m, const RunReport& r);

}  // namespace sc::demo::haptic
