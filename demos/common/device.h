// SPDX-License-Identifier: MIT
// Haptic and input devices behind one interface (manual 9-10.3): the haptic loop
// polls a 6-DOF pose and hands back the wrench to render. Adding a device is one
// class plus a line in makeDevice().
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "smartcollision/types.h"

namespace sc::demo {

/// A device pose in world coordinates: position [m] and unit quaternion (w, x, y, z).
struct DevicePose {
  double position[3] = {0, 0, 0};
  double orientation[4] = {1, 0, 0, 0};
};

/// The device pose of a position and a unit quaternion.
DevicePose devicePose(const Vec3& position, const Quat& orientation);

/// Force [N] and torque [N m] for the device to render (world frame).
struct Wrench {
  double force[3] = {0, 0, 0};
  double torque[3] = {0, 0, 0};
};

class Device {
 public:
  virtual ~Device() = default;
  virtual const char* name() const = 0;
  /// Haptic thread: the current pose. False when the device has no pose yet or failed.
  virtual bool poll(DevicePose& out) = 0;
  /// Haptic thread: the wrench to render (devices without actuators ignore or log it).
  virtual void render(const Wrench& /*w*/) {}
  /// True when a recorded device has played its whole recording.
  virtual bool finished() const { return false; }
  /// Graphics thread: the window exists; devices fed by window events attach here.
  virtual void attachWindow() {}
  /// Graphics thread: a key the viewer did not use.
  virtual void key(unsigned char /*k*/) {}
  /// One line for the on-screen overlay (mapping help, state).
  virtual std::string status() const { return name(); }
  /// Sets the pose a relative device starts from (mouse, SpaceMouse).
  virtual void setHome(const DevicePose& /*home*/) {}
};

/// "mouse", "spacemouse" or "script:FILE". Null with `error` set on failure; a
/// SpaceMouse that cannot be opened falls back to the mouse with a message on stderr.
std::unique_ptr<Device> makeDevice(const std::string& spec, std::string& error);

/// Mouse and keyboard through GLUT (device_mouse.cpp).
std::unique_ptr<Device> makeMouseDevice();
/// 3Dconnexion SpaceMouse through libspnav; null with `error` when the library was
/// not found at build time or spacenavd does not answer (device_spacemouse.cpp).
std::unique_ptr<Device> makeSpaceMouseDevice(std::string& error);
/// How a script device plays its file.
struct ScriptPlayback {
  /// Forward, backward, forward, ... without end (a soak). The reversal keeps the pose
  /// continuous, where restarting would jump from the last pose back to the first.
  bool ping_pong = false;
  /// Keep every rendered wrench (wrenchLogOf); off, memory stays flat however long it runs.
  bool log_wrenches = true;
  /// Seconds since the start of playback; empty: the wall clock from the first poll.
  /// A lock-step run (haptic_coupling --lockstep) drives the script on simulated time.
  std::function<double()> clock;
};
/// Replays a pose file `t x y z qw qx qy qz` (device_script.cpp) and logs the wrenches.
std::unique_ptr<Device> makeScriptDevice(const std::string& path, std::string& error,
                                         const ScriptPlayback& playback = {});

/// The wrenches a script device was given, with the script time of each.
struct WrenchLog {
  std::vector<double> t;
  std::vector<Wrench> wrench;
};
/// The log of a device made by makeScriptDevice; null for other devices.
const WrenchLog* wrenchLogOf(const Device& device);

}  // namespace sc::demo
