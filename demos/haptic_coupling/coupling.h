// SPDX-License-Identifier: MIT
// The coupling loops: the haptic loop (1 kHz: poll the device, the coupling's
// reaction from the latest body state to the device) and the physics loop (apply
// the coupling to the tool with the latest device pose, step Bullet +
// SmartCollision), as two threads or, with --lockstep, in turn on simulated time.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <string>
#include <thread>

#include "../common/device.h"
#include "handoff.h"
#include "metrics.h"
#include "scenes.h"

namespace sc::demo::haptic {

constexpr double kHapticHz = 1000.0;

class CouplingLoops {
 public:
  using Clock = std::chrono::steady_clock;

  /// Couples `device` to the scene's tool, physics at `physics_hz` (the scene's step);
  /// `scene` outlives the loops.
  CouplingLoops(HapticScene& scene, std::unique_ptr<Device> device, double physics_hz);
  ~CouplingLoops() { stop(); }
  CouplingLoops(const CouplingLoops&) = delete;
  CouplingLoops& operator=(const CouplingLoops&) = delete;

  /// The haptic and physics threads.
  void start();
  void stop();
  /// --lockstep: the haptic samples and physics steps of `seconds` of simulated time in
  /// this thread, on a simulated clock (`clock`, which drives the script device), so
  /// the outcome does not depend on how loaded the machine is. The threaded run is
  /// what the rates and periods of docs/benchmarks.md measure.
  void runLockstep(double seconds, std::atomic<double>& clock);

  bool running() const { return running_; }
  Device& device() { return *device_; }
  const Device& device() const { return *device_; }
  const sc::haptics::VirtualCoupling& coupling() const { return *coupling_; }
  const LoopMetrics& metrics() const { return metrics_; }
  /// The latest device pose and tool state, as the loops handed them over.
  PoseWords devicePose() const;
  StateWords bodyState() const;
  /// The JSON report of a finished run in `scene_name`.
  std::string json(const std::string& scene_name) const;

 private:
  void physicsLoop();
  void physicsStep();
  void recordHealth(const sc::haptics::BodyState& body, const sc::haptics::CouplingWrench& w);
  void hapticLoop();
  void hapticSample(double interval);
  void checkForceJump(const Vec3& force, double interval, double body_interval);

  HapticScene& scene_;
  std::unique_ptr<Device> device_;
  double physics_hz_, physics_dt_;
  sc::haptics::CouplingDesign design_;
  std::unique_ptr<sc::haptics::VirtualCoupling> coupling_;
  sc::haptics::PassivityReport passivity_;
  sc::haptics::CouplingEnergyMonitor monitor_;  ///< physics thread

  SeqLock<7> device_pose_;      ///< haptic -> physics, graphics
  SeqLock<15> body_state_;      ///< physics -> haptic, graphics
  PoseWords physics_device_{};  ///< physics thread: the last device pose read
  StateWords haptic_body_{};    ///< haptic thread: the last body state read
  std::atomic<bool> running_{false};
  std::thread physics_, haptic_;
  Clock::time_point start_time_;
  LoopMetrics metrics_;
};

}  // namespace sc::demo::haptic
