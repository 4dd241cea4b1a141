// SPDX-License-Identifier: MIT
// What the viewer draws: the ground, the block, the tool where the physics loop last
// put it, the device's pose as a small green cube, and the overlay text with the
// loops' rates.
#pragma once

#include <string>
#include <vector>

#include "../common/viewer.h"
#include "coupling.h"
#include "scenes.h"

namespace sc::demo::haptic {

class Renderer {
 public:
  Renderer(const std::string& scene_name, const HapticScene& scene, const CouplingLoops& loops)
      : scene_name_(scene_name), scene_(scene), loops_(loops) {}

  void collect(std::vector<DrawItem>& items);
  std::string overlay();
  float targetY() const { return 0.07f; }
  float distance() const { return 0.55f; }

 private:
  using Clock = CouplingLoops::Clock;

  std::string scene_name_;
  const HapticScene& scene_;
  const CouplingLoops& loops_;
  long frames_ = 0, rate_haptic_ = 0, rate_physics_ = 0, rate_frames_ = 0;
  double haptic_rate_ = 0.0, physics_rate_ = 0.0, frame_rate_ = 0.0;
  Clock::time_point rate_time_ = Clock::now();
};

}  // namespace sc::demo::haptic
