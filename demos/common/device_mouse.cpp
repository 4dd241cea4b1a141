// SPDX-License-Identifier: MIT
// Mouse and keyboard as a 6-DOF device (GLUT callbacks, graphics thread):
//   left drag          x (right) and y (up), 0.5 mm per pixel
//   shift + left drag  z (up/down on the screen moves away/towards the viewer)
//   wheel              z, 5 mm per notch
//   i / k              rotate about x (+/- 5 degrees)
//   j / l              rotate about y
//   u / o              rotate about z
//   space              back to the home pose
// The device replaces the viewer's mouse handlers: the camera stays where it is.
#include <GL/freeglut.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>

#include "device.h"
#include "smartcollision/types.h"

namespace sc::demo {

namespace {

constexpr double kMetresPerPixel = 0.0005;
constexpr double kWheelStep = 0.005;
constexpr double kKeyAngle = 5.0 * kPi / 180.0;

class MouseDevice;
MouseDevice* g_mouse = nullptr;

class MouseDevice : public Device {
 public:
  MouseDevice() { g_mouse = this; }
  ~MouseDevice() override {
    if (g_mouse == this) g_mouse = nullptr;
  }
  const char* name() const override { return "mouse"; }

  bool poll(DevicePose& out) override {
    std::lock_guard<std::mutex> lock(mutex_);
    out = devicePose(Vec3(position_[0], position_[1], position_[2]), orientation_);
    return true;
  }

  void render(const Wrench& w) override {
    std::lock_guard<std::mutex> lock(mutex_);
    last_ = w;
  }

  void setHome(const DevicePose& home) override {
    std::lock_guard<std::mutex> lock(mutex_);
    home_ = home;
    goHome();
  }

  void attachWindow() override {
    glutMouseFunc(&MouseDevice::onMouse);
    glutMotionFunc(&MouseDevice::onMotion);
  }

  void key(unsigned char k) override {
    if (k == ' ') {
      std::lock_guard<std::mutex> lock(mutex_);
      goHome();
      return;
    }
    // Turns about +x, -x, +y, -y, +z, -z.
    static const char kTurnKeys[] = "ikjluo";
    const char* at = k != 0 ? std::strchr(kTurnKeys, k) : nullptr;
    if (at == nullptr) return;
    const int i = static_cast<int>(at - kTurnKeys);
    const double angle = (i % 2 == 0 ? 1.0 : -1.0) * kKeyAngle;
    std::lock_guard<std::mutex> lock(mutex_);
    orientation_ = (Quat(Eigen::AngleAxisd(angle, Vec3::Unit(i / 2))) * orientation_).normalized();
  }

  std::string status() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    char buf[200];
    std::snprintf(buf, sizeof(buf),
                  "mouse: drag x/y, shift-drag or wheel z, i/k j/l u/o rotate, space home\n"
                  "device (%.3f %.3f %.3f) m   rendered force %.1f N",
                  position_[0], position_[1], position_[2],
                  std::sqrt(last_.force[0] * last_.force[0] + last_.force[1] * last_.force[1] +
                            last_.force[2] * last_.force[2]));
    return buf;
  }

 private:
  void goHome() {
    for (int k = 0; k < 3; ++k) position_[k] = home_.position[k];
    orientation_ = Quat(home_.orientation[0], home_.orientation[1], home_.orientation[2],
                        home_.orientation[3]);
  }

  static void onMouse(int button, int state, int x, int y) {
    if (g_mouse == nullptr) return;
    std::lock_guard<std::mutex> lock(g_mouse->mutex_);
    if (button == GLUT_LEFT_BUTTON) {
      g_mouse->dragging_ = state == GLUT_DOWN;
      g_mouse->shift_ = (glutGetModifiers() & GLUT_ACTIVE_SHIFT) != 0;
      g_mouse->last_x_ = x;
      g_mouse->last_y_ = y;
    } else if (state == GLUT_DOWN && (button == 3 || button == 4)) {
      g_mouse->position_[2] += button == 3 ? -kWheelStep : kWheelStep;
    }
  }

  static void onMotion(int x, int y) {
    if (g_mouse == nullptr) return;
    std::lock_guard<std::mutex> lock(g_mouse->mutex_);
    if (!g_mouse->dragging_) return;
    const double dx = kMetresPerPixel * (x - g_mouse->last_x_);
    const double dy = -kMetresPerPixel * (y - g_mouse->last_y_);
    if (g_mouse->shift_) {
      g_mouse->position_[2] -= dy;
    } else {
      g_mouse->position_[0] += dx;
      g_mouse->position_[1] += dy;
    }
    g_mouse->last_x_ = x;
    g_mouse->last_y_ = y;
  }

  mutable std::mutex mutex_;
  DevicePose home_;
  double position_[3] = {0, 0, 0};
  Quat orientation_ = Quat::Identity();
  Wrench last_;
  bool dragging_ = false, shift_ = false;
  int last_x_ = 0, last_y_ = 0;
};

}  // namespace

std::unique_ptr<Device> makeMouseDevice() { return std::make_unique<MouseDevice>(); }

}  // namespace sc::demo
