// SPDX-License-Identifier: MIT
// Virtual coupling: step response, passivity against a contact, force continuity in
// sliding contact, and the pose-script parser.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <string>

#include "bullet_world.h"
#include "smartcollision/haptics/virtual_coupling.h"

namespace sc::test {
namespace {

using haptics::CouplingDesign;
using haptics::CouplingEnergyMonitor;
using haptics::CouplingPose;
using haptics::CouplingWrench;
using haptics::PoseScript;
using haptics::VirtualCoupling;

constexpr double kHz = 1000.0;
constexpr double kHalf = 0.05;  // box half extent [m]

struct Rig {
  explicit Rig(double gravity = 0.0, bool floor = false)
      : world(bullet::ContactModel::Potential, gravity, kHz) {
    if (floor) world.addGround();
    body = world.addBody(boxShape(btVector3(btScalar(kHalf), btScalar(kHalf), btScalar(kHalf))),
                         1.0, btVector3(0, btScalar(floor ? kHalf + 0.002 : 0.0), 0));
    body->setFlags(body->getFlags() | BT_DISABLE_WORLD_GRAVITY);
    body->setGravity(btVector3(0, 0, 0));
    design.physics_dt = design.haptic_dt = 1.0 / kHz;
  }
  haptics::CouplingGains gains() const { return haptics::designCouplingGains(*body, design); }

  /// One physics step driven by `coupling` towards `device`; the wrench applied.
  CouplingWrench step(const VirtualCoupling& coupling, const CouplingPose& device,
                      CouplingEnergyMonitor* monitor = nullptr) {
    const CouplingWrench w = coupling.apply(device, *body);
    if (monitor != nullptr) monitor->beforeStep(coupling, device, *body, w);
    world.step();
    if (monitor != nullptr) monitor->afterStep(*body);
    return w;
  }

  BulletWorld world;
  btRigidBody* body = nullptr;
  CouplingDesign design;
};

/// Peak overshoot of a step of size `step` along x for damping ratio zeta.
double stepOvershoot(double zeta, double* final_error) {
  Rig rig;
  rig.design.damping_ratio = zeta;
  const VirtualCoupling coupling(rig.gains());
  const double step = 0.0004;  // small enough that nothing saturates
  CouplingPose device;
  device.position = Vec3(step, 0, 0);
  double peak = 0.0;
  for (int i = 0; i < 600; ++i) {
    const CouplingWrench w = rig.step(coupling, device);
    EXPECT_FALSE(w.clamped) << "step " << i;
    peak = std::max(peak, double(rig.body->getCenterOfMassPosition().x()));
  }
  *final_error = std::abs(double(rig.body->getCenterOfMassPosition().x()) - step);
  return (peak - step) / step;
}

TEST(VirtualCouplingTest, GainsPassTheSampledSpringBound) {
  Rig rig;
  const haptics::CouplingGains g = rig.gains();
  EXPECT_NEAR(g.linear_stiffness, 1.0 * std::pow(2 * kPi / (20 * 1e-3), 2), 1.0);
  const haptics::PassivityReport p = haptics::checkPassivity(g, rig.design);
  EXPECT_TRUE(p.body_side) << p.body_margin;
  EXPECT_FALSE(p.device_side);  // device damping unknown
  EXPECT_NEAR(p.required_device_damping, 0.5 * g.linear_stiffness * 1e-3, 1e-9);
  // A known device damping lowers the render scale until the device side passes.
  rig.design.device_damping = 2.0;
  rig.design.device_angular_damping = 0.05;
  const haptics::CouplingGains scaled = rig.gains();
  EXPECT_LT(scaled.render_scale, 1.0);
  EXPECT_TRUE(haptics::checkPassivity(scaled, rig.design).device_side);
  // Too little damping for the sample period fails the body side.
  haptics::CouplingGains weak = g;
  weak.linear_damping = 0.4 * g.linear_stiffness * 1e-3;
  EXPECT_FALSE(haptics::checkPassivity(weak, rig.design).body_side);
}

TEST(VirtualCouplingTest, PullsFreeBodyWithoutOvershootAtCriticalDamping) {
  double error = 0.0;
  const double critical = stepOvershoot(1.0, &error);
  EXPECT_LT(critical, 0.01) << "critically damped coupling overshoots";
  EXPECT_LT(error, 1e-6);
  // zeta = 0.5: the continuous overshoot is exp(-pi zeta / sqrt(1 - zeta^2)) = 16.3 %.
  const double under = stepOvershoot(0.5, &error);
  EXPECT_NEAR(under, std::exp(-kPi * 0.5 / std::sqrt(0.75)), 0.04);
}

TEST(VirtualCouplingTest, RotationConvergesWithoutOvershoot) {
  Rig rig;
  const VirtualCoupling coupling(rig.gains());
  CouplingPose device;
  const double angle = 0.02;
  device.orientation = Quat(Eigen::AngleAxisd(angle, Vec3::UnitY()));
  double peak = 0.0;
  for (int i = 0; i < 800; ++i) {
    rig.step(coupling, device);
    const Vec3 r = haptics::rotationVector(haptics::bodyStateOf(*rig.body).pose.orientation);
    peak = std::max(peak, r.y());
  }
  const Vec3 r = haptics::rotationVector(haptics::bodyStateOf(*rig.body).pose.orientation);
  EXPECT_NEAR(r.y(), angle, 1e-5);
  EXPECT_LT((peak - angle) / angle, 0.02);
}

TEST(VirtualCouplingTest, SaturatedPullIsLimited) {
  Rig rig;
  const VirtualCoupling coupling(rig.gains());
  CouplingPose device;
  device.position = Vec3(0.3, 0, 0);
  for (int i = 0; i < 50; ++i) {
    const CouplingWrench w = rig.step(coupling, device);
    EXPECT_LE(w.force.norm(), coupling.gains().max_force * (1 + 1e-9));
  }
  for (int i = 0; i < 5000; ++i) rig.step(coupling, device);
  EXPECT_NEAR(double(rig.body->getCenterOfMassPosition().x()), 0.3, 1e-4);
}

/// The device presses the box into a static floor and lifts it off, four times,
/// with a lateral wobble; returns the monitor.
CouplingEnergyMonitor pressAndRelease(double damping_scale, double* device_work) {
  Rig rig(0.0, true);
  haptics::CouplingGains g = rig.gains();
  g.linear_damping *= damping_scale;
  g.angular_damping *= damping_scale;
  const VirtualCoupling coupling(g);
  std::string text;
  const double top = kHalf + 0.002;
  for (int cycle = 0; cycle < 4; ++cycle) {
    const double t0 = 0.4 * cycle;
    char line[256];
    std::snprintf(line, sizeof(line),
                  "%g 0 %g 0 1 0 0 0\n%g 0.01 %g 0 1 0 0 0\n%g 0.02 %g 0 0.998 0 0.06 0\n",
                  t0 + 0.001, top + 0.01, t0 + 0.15, kHalf - 0.004, t0 + 0.25, top + 0.01);
    text += line;
  }
  const Result<PoseScript> script = PoseScript::parse(text);
  EXPECT_TRUE(script.ok()) << script.status().message();
  CouplingEnergyMonitor monitor;
  const int steps = int(std::lround((script.value().duration() + 0.3) * kHz));
  for (int i = 0; i < steps; ++i) rig.step(coupling, script.value().sample(i / kHz), &monitor);
  *device_work = monitor.deviceWork();
  return monitor;
}

TEST(VirtualCouplingTest, InAndOutOfContactGeneratesNoEnergy) {
  double device_work = 0.0;
  const CouplingEnergyMonitor m = pressAndRelease(1.0, &device_work);
  EXPECT_EQ(m.steps(), 1750);
  // The damper dissipates: net generated energy is negative, and never rises above
  // a round-off tolerance at any step of the run.
  RecordProperty("generated_J", std::to_string(m.generated()));
  RecordProperty("max_generated_J", std::to_string(m.maxGenerated()));
  RecordProperty("device_work_J", std::to_string(device_work));
  EXPECT_LT(m.generated(), 0.0);
  EXPECT_LT(m.maxGenerated(), 1e-4) << "generated " << m.generated() << " J";
  EXPECT_GT(std::abs(device_work), 1e-3);  // the run did work
}

TEST(VirtualCouplingTest, EnergyMonitorSeesAnUndampedSampledSpring) {
  // Without damping the sampled spring adds 1/2 k |dx|^2 every step: the monitor
  // must report it (the bound b > k T / 2 is what keeps the coupling passive).
  double device_work = 0.0;
  const CouplingEnergyMonitor m = pressAndRelease(0.0, &device_work);
  RecordProperty("generated_J", std::to_string(m.generated()));
  EXPECT_GT(m.generated(), 0.0);
}

TEST(VirtualCouplingTest, ForceIsContinuousWhileSliding) {
  Rig rig(0.0, true);
  const VirtualCoupling coupling(rig.gains());
  CouplingPose device;
  double max_jump = 0.0, max_force = 0.0;
  Vec3 previous = Vec3::Zero();
  bool first = true;
  for (int i = 0; i < 1800; ++i) {
    const double t = i / kHz;
    // Descend 5 mm/s from the start pose onto the floor and 0.3 mm into it (a 30 N
    // push), slide at 0.1 m/s along x, then back.
    const double x = t < 0.6 ? 0.0 : t < 1.2 ? 0.1 * (t - 0.6) : 0.06 - 0.1 * (t - 1.2);
    device.position = Vec3(x, kHalf + 0.002 - std::min(0.005 * t, 0.0023), 0.0);
    rig.step(coupling, device);
    const Vec3 f = coupling.reaction(device, haptics::bodyStateOf(*rig.body)).force;
    if (!first) max_jump = std::max(max_jump, (f - previous).norm());
    max_force = std::max(max_force, f.norm());
    previous = f;
    first = false;
  }
  RecordProperty("max_jump_N", std::to_string(max_jump));
  RecordProperty("max_force_N", std::to_string(max_force));
  EXPECT_GT(max_force, 5.0);  // it did press
  // Speeds at most 0.1 m/s, lockstep at 1 kHz (docs/haptics.md: 2 k_t v T + 0.1 max_force).
  EXPECT_LT(max_jump, haptics::forceJumpBound(coupling.gains(), 0.1, 1.0 / kHz, 1.0 / kHz))
      << "max force " << max_force;
  EXPECT_GT(double(rig.body->getCenterOfMassPosition().y()),
            kHalf - 0.002);  // still above the floor
}

TEST(VirtualCouplingTest, ImpactJumpStaysWithinItsBound) {
  // The device lowers the box 20 mm at 0.1 m/s onto the floor and 0.5 mm into it.
  // At the impact the contact model stops the box within a step or two, so the
  // damper's force jumps by up to b_t v (impactJumpBound); before and after that
  // window the sliding bound holds.
  Rig rig(0.0, true);
  const double top = kHalf + 0.02;
  rig.body->getWorldTransform().setOrigin(btVector3(0, btScalar(top), 0));
  const VirtualCoupling coupling(rig.gains());
  const haptics::CouplingGains& g = coupling.gains();
  CouplingPose device;
  Vec3 previous = Vec3::Zero();
  double impact_jump = 0.0, other_jump = 0.0;
  int since_contact = -1;  // samples since the contact's onset; -1 before it
  for (int i = 0; i < 600; ++i) {
    device.position = Vec3(0, top - std::min(0.1 * i / kHz, 0.0205), 0);
    rig.step(coupling, device);
    // Onset: the box within 0.5 mm of the floor (geometry, not the plugin's counts:
    // the rows stop the box at the surface, before any penetration is seen).
    if (since_contact < 0 && double(rig.body->getCenterOfMassPosition().y()) < kHalf + 5e-4)
      since_contact = 0;
    const Vec3 f = coupling.reaction(device, haptics::bodyStateOf(*rig.body)).force;
    const bool impact = since_contact >= 0 && since_contact < 20;
    double& worst = impact ? impact_jump : other_jump;
    if (i > 0) worst = std::max(worst, (f - previous).norm());
    if (since_contact >= 0) ++since_contact;
    previous = f;
  }
  RecordProperty("impact_jump_N", std::to_string(impact_jump));
  RecordProperty("other_jump_N", std::to_string(other_jump));
  ASSERT_GE(since_contact, 0) << "the box never touched the floor";
  const double sliding = haptics::forceJumpBound(g, 0.1, 1.0 / kHz, 1.0 / kHz);
  EXPECT_GT(impact_jump, 0.5 * g.linear_damping * 0.1) << "the impact should show b_t v";
  EXPECT_LT(impact_jump, haptics::impactJumpBound(g, 0.1, 1.0 / kHz, 1.0 / kHz));
  EXPECT_LT(other_jump, sliding);
}

TEST(VirtualCouplingTest, PoseScriptInterpolates) {
  const Result<PoseScript> s = PoseScript::parse(
      "# t x y z qw qx qy qz\n"
      "0 0 0 0 1 0 0 0\n"
      "\n"
      "1.0 1 2 -2 0 0 0 1   # half a turn about z\n");
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s.value().samples().size(), 2u);
  const CouplingPose mid = s.value().sample(0.5);
  EXPECT_NEAR((mid.position - Vec3(0.5, 1, -1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(haptics::rotationVector(mid.orientation).z(), kPi / 2, 1e-9);
  EXPECT_NEAR((s.value().sample(-1).position).norm(), 0.0, 1e-12);
  EXPECT_NEAR((s.value().sample(5).position - Vec3(1, 2, -2)).norm(), 0.0, 1e-12);
}

TEST(VirtualCouplingTest, PoseScriptRefusesAFifoWithoutBlocking) {
  const std::string fifo = "/tmp/sc_pose_fifo_" + std::to_string(::getpid());
  std::remove(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::future<Result<PoseScript>> load =
      std::async(std::launch::async, [&fifo] { return PoseScript::load(fifo); });
  if (load.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);  // lets it finish
    if (writer >= 0) ::close(writer);
    load.wait();
    std::remove(fifo.c_str());
    FAIL() << "loading a FIFO blocked";
  }
  const Result<PoseScript> r = load.get();
  std::remove(fifo.c_str());
  EXPECT_EQ(r.status().code(), ErrorCode::File);
  EXPECT_NE(r.status().message().find("not a regular file"), std::string::npos)
      << r.status().message();
}

TEST(VirtualCouplingTest, PoseScriptRejectsMalformedLines) {
  struct Case {
    const char* text;
    const char* message;
  };
  const Case cases[] = {
      {"0 0 0 0 1 0 0 0\n0.1 0 0 1\n", "line 2: expected 8 numbers"},
      {"0 0 0 0 1 0 0 0 7\n", "line 1: expected 8 numbers"},
      {"0 0 x 0 1 0 0 0\n", "line 1: 'x' is not a number"},
      {"0 0 0 0 1 0 0 0\n0.5 0 0 nan 1 0 0 0\n", "line 2: non-finite"},
      {"0 0 0 0 0 0 0 0\n", "line 1: zero quaternion"},
      {"1 0 0 0 1 0 0 0\n0.5 0 0 0 1 0 0 0\n", "line 2: time"},
      {"0 0 0 0 1 0 0 0\n0 0 0 0 1 0 0 0\n", "line 2: time"},
      {"0 0 0 0 1,0 0 0\n", "line 1: '1,0' is not a number"},
      {"# only a comment\n\n", "no sample"},
      {"", "no sample"},
  };
  for (const Case& c : cases) {
    const Result<PoseScript> r = PoseScript::parse(c.text);
    EXPECT_FALSE(r.ok()) << c.text;
    EXPECT_EQ(r.status().code(), ErrorCode::InvalidArgument) << c.text;
    EXPECT_NE(r.status().message().find(c.message), std::string::npos)
        << "'" << r.status().message() << "' lacks '" << c.message << "'";
  }
  const Result<PoseScript> missing = PoseScript::load("/nonexistent/pose.txt");
  EXPECT_EQ(missing.status().code(), ErrorCode::File);
}

}  // namespace
}  // namespace sc::test
