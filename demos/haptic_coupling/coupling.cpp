// SPDX-License-Identifier: MIT
#include "coupling.h"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "../common/cli.h"

namespace sc::demo::haptic {
namespace {

constexpr double kMaxDeviceSpeed = 0.1;  ///< [m/s] the scripted runs stay below (force-jump bound)
/// Haptic samples after a missed deadline (either loop) that the force-jump bound does
/// not cover: the coupling's time constant (1 / omega, about 3 ms) several times over.
constexpr int kSettleSamples = 20;

/// A haptic loop's deadline is a millisecond: ask for FIFO scheduling above every
/// ordinary thread (the physics thread included), as haptic applications do. It
/// needs CAP_SYS_NICE or an rtprio limit; without them the loop runs as before.
/// Safe because the loop sleeps between samples (microseconds of work per period).
bool raiseToRealTime() {
  sched_param param{};
  param.sched_priority = sched_get_priority_min(SCHED_FIFO) + 10;
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0;
}

}  // namespace

CouplingLoops::CouplingLoops(HapticScene& scene, std::unique_ptr<Device> device, double physics_hz)
    : scene_(scene),
      device_(std::move(device)),
      physics_hz_(physics_hz),
      physics_dt_(1.0 / physics_hz) {
  design_.physics_dt = physics_dt_;
  design_.haptic_dt = 1.0 / kHapticHz;
  coupling_ = std::make_unique<sc::haptics::VirtualCoupling>(
      sc::haptics::designCouplingGains(scene_.tool(), design_));
  passivity_ = sc::haptics::checkPassivity(coupling_->gains(), design_);
  DevicePose home;
  for (int k = 0; k < 3; ++k) home.position[k] = scene_.toolHome()[k];
  device_->setHome(home);
  sc::haptics::CouplingPose home_pose;
  home_pose.position = scene_.toolHome();
  device_pose_.write(wordsOf(home_pose));
  body_state_.write(wordsOf(sc::haptics::bodyStateOf(scene_.tool())));
  device_pose_.read(physics_device_);
  body_state_.read(haptic_body_);
}

void CouplingLoops::start() {
  start_time_ = Clock::now();
  running_ = true;
  physics_ = std::thread([this] { physicsLoop(); });
  haptic_ = std::thread([this] { hapticLoop(); });
}

void CouplingLoops::runLockstep(double seconds, std::atomic<double>& clock) {
  metrics_.lockstep = true;
  const auto wall = Clock::now();
  const long samples = std::lround(seconds * kHapticHz);
  for (long k = 0; k < samples; ++k) {
    clock = double(k) / kHapticHz;
    hapticSample(k == 0 ? 0.0 : 1.0 / kHapticHz);
    const double until = double(k + 1) / kHapticHz;  // physics catches up to the next sample
    while (double(metrics_.physics_count.load() + 1) * physics_dt_ <= until + 1e-9) physicsStep();
  }
  metrics_.elapsed = double(samples) / kHapticHz;
  metrics_.wall_seconds = std::chrono::duration<double>(Clock::now() - wall).count();
}

void CouplingLoops::stop() {
  running_ = false;
  if (haptic_.joinable()) haptic_.join();
  if (physics_.joinable()) physics_.join();
  metrics_.elapsed = std::chrono::duration<double>(Clock::now() - start_time_).count();
  metrics_.wall_seconds = metrics_.elapsed;
}

PoseWords CouplingLoops::devicePose() const {
  PoseWords d{};
  device_pose_.read(d);
  return d;
}

StateWords CouplingLoops::bodyState() const {
  StateWords w{};
  body_state_.read(w);
  return w;
}

std::string CouplingLoops::json(const std::string& scene_name) const {
  RunReport r;
  r.scene = scene_name;
  r.device = device_->name();
  r.haptic_dt = 1.0 / kHapticHz;
  r.physics_dt = physics_dt_;
  r.max_device_speed = kMaxDeviceSpeed;
  r.gains = coupling_->gains();
  r.passivity = passivity_;
  r.monitor = &monitor_;
  r.tool_triangles = scene_.toolTriangles();
  r.fixed_triangles = scene_.fixedTriangles();
  r.final_state = sc::haptics::bodyStateOf(scene_.tool());
  r.final_rotation_vector = scene_.meshRotationVector(r.final_state);
  r.inserted_depth = scene_.insertedDepth(r.final_state);
  r.inside = scene_.inside(r.final_state);
  return metricsJson(metrics_, r);
}

void CouplingLoops::physicsLoop() {
  auto next = Clock::now();
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(physics_dt_));
  while (running_) {
    next += period;
    physicsStep();
    const auto now = Clock::now();
    if (next > now)
      std::this_thread::sleep_until(next);
    else if (now - next > 20 * period)
      next = now;  // far behind: do not try to catch up in a burst
  }
}

/// One physics step: the coupling with the latest device pose, Bullet + SmartCollision,
/// the body state handed to the haptic loop.
void CouplingLoops::physicsStep() {
  device_pose_.read(physics_device_);  // kept as it was if the writer is mid-write
  const sc::haptics::CouplingPose device = scene_.bodyTarget(poseOf(physics_device_.data()));
  btRigidBody& tool = scene_.tool();
  sc::bullet::ScDynamicsWorld& world = scene_.world();
  const auto t0 = Clock::now();
  const sc::haptics::CouplingWrench w = coupling_->apply(device, tool);
  monitor_.beforeStep(*coupling_, device, tool, w);
  world.stepSimulation(btScalar(physics_dt_), 1, btScalar(physics_dt_));
  monitor_.afterStep(tool);
  const double step = std::chrono::duration<double>(Clock::now() - t0).count();
  metrics_.step_seconds += step;
  metrics_.step_max = std::max(metrics_.step_max, step);
  if (step > physics_dt_) ++metrics_.steps_over_period;
  metrics_.max_depth = std::max(metrics_.max_depth.load(), world.plugin().stats().max_depth);
  metrics_.generated = monitor_.generated();
  const sc::haptics::BodyState body = sc::haptics::bodyStateOf(tool);
  recordHealth(body, w);
  StateWords state = wordsOf(body);
  state[13] = double(metrics_.physics_count.load() + 1);
  state[14] = world.plugin().stats().touching > 0 ? 1.0 : 0.0;
  body_state_.write(state);
  ++metrics_.physics_count;
}

/// Physics thread, after each step: what a soak watches (NaN, energy, memory).
void CouplingLoops::recordHealth(const sc::haptics::BodyState& body,
                                 const sc::haptics::CouplingWrench& w) {
  if (!finite(body) || !finite(w)) ++metrics_.non_finite_steps;
  metrics_.max_kinetic = std::max(metrics_.max_kinetic, kineticEnergy(scene_.tool()));
  const long step = metrics_.physics_count.load() + 1;
  const long per_second = std::lround(physics_hz_);
  if (step == per_second) metrics_.rss_after_1s_kb = residentKb();
  if (step == 60 * per_second) metrics_.rss_after_60s_kb = residentKb();
}

void CouplingLoops::hapticLoop() {
  metrics_.haptic_fifo = raiseToRealTime();
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / kHapticHz));
  auto next = Clock::now();
  Clock::time_point last;
  bool first = true;
  while (running_) {
    const auto now = Clock::now();
    hapticSample(first ? 0.0 : std::chrono::duration<double>(now - last).count());
    last = now;
    first = false;
    next += period;
    std::this_thread::sleep_until(next);
    if (Clock::now() - next > 20 * period) next = Clock::now();
  }
}

/// One haptic sample, `interval` seconds after the previous one (0 for the first):
/// poll the device, the reaction from the latest body state to the device, and the
/// force-continuity check.
void CouplingLoops::hapticSample(double interval) {
  LoopMetrics& m = metrics_;
  const bool first = m.haptic_count.load() == 0;
  if (!first) m.periods.add(interval);
  DevicePose p;
  if (device_->poll(p)) {
    sc::haptics::CouplingPose pose;
    pose.position = Vec3(p.position[0], p.position[1], p.position[2]);
    pose.orientation =
        Quat(p.orientation[0], p.orientation[1], p.orientation[2], p.orientation[3]).normalized();
    device_pose_.write(wordsOf(pose));
    body_state_.read(haptic_body_);  // kept as it was if the writer is mid-write
    const StateWords& s = haptic_body_;
    const sc::haptics::CouplingWrench r = coupling_->reaction(scene_.bodyTarget(pose), stateOf(s));
    if (!finite(stateOf(s)) || !finite(r)) ++m.non_finite_samples;
    Wrench out;
    for (int k = 0; k < 3; ++k) {
      out.force[k] = r.force[k];
      out.torque[k] = r.torque[k];
    }
    device_->render(out);
    const bool contact = s[14] > 0.5;
    if (contact && !m.previous_contact) {
      m.since_impact = 0;
      ++m.impacts;
    }
    m.previous_contact = contact;
    if (!first) checkForceJump(r.force, interval, (s[13] - m.previous_steps) * physics_dt_);
    m.previous_steps = s[13];
    m.max_coupling_force = std::max(m.max_coupling_force, r.force.norm());
    m.last_force = r.force.norm();
    m.previous_force = r.force;
  }
  ++m.haptic_count;
}

/// The bound for this pair of samples: the device moved for `interval`, the body for
/// `body_interval` (the physics steps taken in between); within kSettleSamples of a
/// contact's onset the impact bound (the body stops at once). It assumes both loops
/// keep their rates: after a missed deadline the body catches up faster than the
/// bound's speed, so pairs within kSettleSamples of one are only counted.
void CouplingLoops::checkForceJump(const Vec3& force, double interval, double body_interval) {
  LoopMetrics& m = metrics_;
  if (interval > 1.5 / kHapticHz || body_interval > 2.5 * physics_dt_) m.since_miss = 0;
  const double jump = (force - m.previous_force).norm();
  m.max_jump_any = std::max(m.max_jump_any, jump);
  const bool impact = m.since_impact < kSettleSamples;
  if (impact) ++m.since_impact;
  if (m.since_miss < kSettleSamples) {
    ++m.since_miss;
    ++m.unchecked_samples;
    return;
  }
  const sc::haptics::CouplingGains& g = coupling_->gains();
  if (impact) {
    const double bound = sc::haptics::impactJumpBound(g, kMaxDeviceSpeed, interval, body_interval);
    m.max_impact_jump = std::max(m.max_impact_jump, jump);
    m.max_impact_ratio = std::max(m.max_impact_ratio, jump / bound);
    return;
  }
  const double bound = sc::haptics::forceJumpBound(g, kMaxDeviceSpeed, interval, body_interval);
  m.max_jump = std::max(m.max_jump, jump);
  m.max_jump_ratio = std::max(m.max_jump_ratio, jump / bound);
}

}  // namespace sc::demo::haptic
