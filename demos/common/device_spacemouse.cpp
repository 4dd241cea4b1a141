// SPDX-License-Identifier: MIT
// 3Dconnexion SpaceMouse through libspnav (spacenavd). Rate control: the cap's
// displacement sets the device's velocity (translation 0.1 m/s and rotation
// 1 rad/s at full deflection, about 350 counts); button 0 returns home. Compiled
// with SC_HAVE_SPNAV only; otherwise makeSpaceMouseDevice reports the missing library.
#include "device.h"

#ifdef SC_HAVE_SPNAV
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>

#include "smartcollision/types.h"

// Last: Debian's spnav.h pulls in Xlib, whose macros (Success, Status, None, Bool)
// would break Eigen and our names; none of them is used here.
#include <spnav.h>
#undef Success
#undef Status
#undef None
#undef Bool
#undef True
#undef False
#endif

namespace sc::demo {

#ifdef SC_HAVE_SPNAV
namespace {

constexpr double kFullScale = 350.0;
constexpr double kSpeed = 0.1;         // m/s at full deflection
constexpr double kAngularSpeed = 1.0;  // rad/s at full deflection

class SpaceMouseDevice : public Device {
 public:
  ~SpaceMouseDevice() override { spnav_close(); }
  const char* name() const override { return "spacemouse"; }

  bool poll(DevicePose& out) override {
    spnav_event ev;
    while (spnav_poll_event(&ev) != 0) {
      if (ev.type == SPNAV_EVENT_MOTION) {
        // spacenavd axes: x right, y up, z into the screen; rx, ry, rz likewise.
        velocity_ = Vec3(ev.motion.x, ev.motion.y, -ev.motion.z) * (kSpeed / kFullScale);
        angular_ = Vec3(ev.motion.rx, ev.motion.ry, -ev.motion.rz) * (kAngularSpeed / kFullScale);
      } else if (ev.type == SPNAV_EVENT_BUTTON && ev.button.press && ev.button.bnum == 0) {
        goHome();
      }
    }
    const auto now = std::chrono::steady_clock::now();
    const double dt =
        started_ ? std::min(0.01, std::chrono::duration<double>(now - last_).count()) : 0.0;
    started_ = true;
    last_ = now;
    position_ += velocity_ * dt;
    const double angle = angular_.norm() * dt;
    if (angle > 0.0)
      orientation_ =
          (Quat(Eigen::AngleAxisd(angle, angular_.normalized())) * orientation_).normalized();
    out = devicePose(position_, orientation_);
    return true;
  }

  void setHome(const DevicePose& home) override {
    home_ = home;
    goHome();
  }

  std::string status() const override { return "spacemouse: push/twist the cap, button 1 home"; }

 private:
  void goHome() {
    position_ = Vec3(home_.position[0], home_.position[1], home_.position[2]);
    orientation_ = Quat(home_.orientation[0], home_.orientation[1], home_.orientation[2],
                        home_.orientation[3]);
  }

  DevicePose home_;
  Vec3 position_ = Vec3::Zero(), velocity_ = Vec3::Zero(), angular_ = Vec3::Zero();
  Quat orientation_ = Quat::Identity();
  std::chrono::steady_clock::time_point last_;
  bool started_ = false;
};

}  // namespace

std::unique_ptr<Device> makeSpaceMouseDevice(std::string& error) {
  if (spnav_open() == -1) {
    error = "cannot connect to spacenavd (is it running?)";
    return nullptr;
  }
  return std::make_unique<SpaceMouseDevice>();
}
#else
std::unique_ptr<Device> makeSpaceMouseDevice(std::string& error) {
  error = "built without libspnav (install libspnav-dev and reconfigure)";
  return nullptr;
}
#endif

}  // namespace sc::demo
