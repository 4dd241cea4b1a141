// SPDX-License-Identifier: MIT
// Script device: replays a recorded pose file in real time (clock started at the
// first poll) and keeps every wrench it is given, for tests and recordings.
#include <chrono>
#include <mutex>

#include "device.h"
#include "smartcollision/bullet/virtual_coupling.h"

namespace sc::demo {

namespace {

class ScriptDevice : public Device {
 public:
  explicit ScriptDevice(bullet::PoseScript script) : script_(std::move(script)) {}
  const char* name() const override { return "script"; }

  bool poll(DevicePose& out) override {
    const auto now = std::chrono::steady_clock::now();
    if (!started_) {
      start_ = now;
      started_ = true;
    }
    const double t = std::chrono::duration<double>(now - start_).count();
    std::lock_guard<std::mutex> lock(mutex_);
    t_ = t;
    const bullet::CouplingPose p = script_.sample(t);
    for (int k = 0; k < 3; ++k) out.position[k] = p.position[k];
    out.orientation[0] = p.orientation.w();
    out.orientation[1] = p.orientation.x();
    out.orientation[2] = p.orientation.y();
    out.orientation[3] = p.orientation.z();
    return true;
  }

  void render(const Wrench& w) override {
    std::lock_guard<std::mutex> lock(mutex_);
    log_.t.push_back(t_);
    log_.wrench.push_back(w);
  }

  bool finished() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return started_ && t_ >= script_.duration();
  }

  std::string status() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    char buf[96];
    std::snprintf(buf, sizeof(buf), "script t = %.2f / %.2f s", t_, script_.duration());
    return buf;
  }

  const WrenchLog& log() const { return log_; }

 private:
  bullet::PoseScript script_;
  std::chrono::steady_clock::time_point start_;
  bool started_ = false;
  double t_ = 0.0;
  WrenchLog log_;
  mutable std::mutex mutex_;
};

}  // namespace

std::unique_ptr<Device> makeScriptDevice(const std::string& path, std::string& error) {
  Result<bullet::PoseScript> script = bullet::PoseScript::load(path);
  if (!script.ok()) {
    error = script.status().message();
    return nullptr;
  }
  return std::make_unique<ScriptDevice>(std::move(script.value()));
}

const WrenchLog* wrenchLogOf(const Device& device) {
  const auto* s = dynamic_cast<const ScriptDevice*>(&device);
  return s != nullptr ? &s->log() : nullptr;
}

}  // namespace sc::demo
