// SPDX-License-Identifier: MIT
// Script device: replays a recorded pose file in real time (clock started at the
// first poll) or on a given clock, once or back and forth, and keeps every wrench it is given (when
// asked), for tests, recordings and soaks.
#include <chrono>
#include <cmath>
#include <mutex>

#include "device.h"
#include "smartcollision/haptics/virtual_coupling.h"

namespace sc::demo {

namespace {

class ScriptDevice : public Device {
 public:
  ScriptDevice(haptics::PoseScript script, const ScriptPlayback& playback)
      : script_(std::move(script)), playback_(playback) {}
  const char* name() const override { return "script"; }

  bool poll(DevicePose& out) override {
    const auto now = std::chrono::steady_clock::now();
    // started_ under the lock too: finished() and status() may run on other threads.
    std::lock_guard<std::mutex> lock(mutex_);
    if (!started_) {
      start_ = now;
      started_ = true;
    }
    const double t =
        playback_.clock ? playback_.clock() : std::chrono::duration<double>(now - start_).count();
    t_ = t;
    const haptics::CouplingPose p = script_.sample(scriptTime(t));
    out = devicePose(p.position, p.orientation);
    return true;
  }

  void render(const Wrench& w) override {
    if (!playback_.log_wrenches) return;
    std::lock_guard<std::mutex> lock(mutex_);
    log_.t.push_back(t_);
    log_.wrench.push_back(w);
  }

  bool finished() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return started_ && !playback_.ping_pong && t_ >= script_.duration();
  }

  std::string status() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    char buf[96];
    std::snprintf(buf, sizeof(buf), "script t = %.2f / %.2f s", t_, script_.duration());
    return buf;
  }

  const WrenchLog& log() const { return log_; }

 private:
  /// Wall time since the first poll -> time in the file.
  double scriptTime(double t) const {
    const double d = script_.duration();
    if (!playback_.ping_pong || d <= 0.0) return t;
    const double u = std::fmod(t, 2.0 * d);
    return u <= d ? u : 2.0 * d - u;
  }

  haptics::PoseScript script_;
  ScriptPlayback playback_;
  std::chrono::steady_clock::time_point start_;
  bool started_ = false;
  double t_ = 0.0;
  WrenchLog log_;
  mutable std::mutex mutex_;
};

}  // namespace

std::unique_ptr<Device> makeScriptDevice(const std::string& path, std::string& error,
                                         const ScriptPlayback& playback) {
  Result<haptics::PoseScript> script = haptics::PoseScript::load(path);
  if (!script.ok()) {
    error = script.status().message();
    return nullptr;
  }
  return std::make_unique<ScriptDevice>(std::move(script.value()), playback);
}

const WrenchLog* wrenchLogOf(const Device& device) {
  const auto* s = dynamic_cast<const ScriptDevice*>(&device);
  return s != nullptr ? &s->log() : nullptr;
}

}  // namespace sc::demo
