// SPDX-License-Identifier: MIT
// Stacking acceptance at 240 Hz, potential and manifold models: a 10-box tower,
// a 15-box pyramid and a 1:100 mass-ratio stack of SmartCollision boxes stand.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bullet_world.h"

namespace sc::test {
namespace {

constexpr double kBox = 1.0;   // edge length [m]
constexpr double kGap = 0.01;  // spawn gap: a pair first seen touching has no depth yet
// 20 s simulated in Release; sanitizer builds run 4 s.
constexpr double kSeconds = SC_TEST_SANITIZED ? 4.0 : 20.0;

struct Watch {
  btRigidBody* body;
  btVector3 start;
};

/// Runs the world and tracks the bodies: horizontal drift, height change over the
/// second half (creep, after settling), tilt, and the largest penetration seen.
struct StackRun {
  double max_drift = 0.0;      ///< largest horizontal displacement of any watched body [m]
  double top_creep = 0.0;      ///< |height change| of the top body over the second half [m]
  double top_sag = 0.0;        ///< spawn height minus final height of the top body [m]
  double max_tilt = 0.0;       ///< largest angle of a body's up axis from vertical [rad]
  double max_depth = 0.0;      ///< largest |TPDV| reported [m]
  double rms_speed_end = 0.0;  ///< RMS speed over the bodies at the end [m/s]
  double ms_per_step = 0.0;
  int recovering_steps = 0;  ///< substeps with a pair pushed apart as first-seen overlapping
};

StackRun run(BulletWorld& w, const std::vector<Watch>& watch, btRigidBody* top, double seconds) {
  StackRun r;
  const int steps = static_cast<int>(std::lround(seconds / w.dt));
  const int settle = steps / 2;
  double top_settled = 0.0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) {
    w.step();
    r.max_depth = std::max(r.max_depth, w.plugin->stats().max_depth);
    r.recovering_steps += w.plugin->stats().recovering > 0 ? 1 : 0;
    for (const Watch& x : watch) {
      const btVector3 p = x.body->getCenterOfMassPosition();
      const double dx = double(p.x() - x.start.x()), dz = double(p.z() - x.start.z());
      r.max_drift = std::max(r.max_drift, std::sqrt(dx * dx + dz * dz));
      const btVector3 up = x.body->getWorldTransform().getBasis() * btVector3(0, 1, 0);
      r.max_tilt = std::max(r.max_tilt, std::acos(std::clamp(double(up.y()), -1.0, 1.0)));
    }
    if (i + 1 == settle) top_settled = double(top->getCenterOfMassPosition().y());
  }
  const auto t1 = std::chrono::steady_clock::now();
  r.ms_per_step = std::chrono::duration<double, std::milli>(t1 - t0).count() / steps;
  r.top_creep = std::abs(double(top->getCenterOfMassPosition().y()) - top_settled);
  double top_start = 0.0;
  for (const Watch& x : watch)
    if (x.body == top) top_start = double(x.start.y());
  r.top_sag = top_start - double(top->getCenterOfMassPosition().y());
  double s2 = 0.0;
  for (const Watch& x : watch) s2 += double(x.body->getLinearVelocity().length2());
  r.rms_speed_end = std::sqrt(s2 / double(watch.size()));
  return r;
}

void report(const char* name, const StackRun& r) {
  std::printf(
      "[%s] drift %.5f m, top sag %.5f m, creep (2nd half) %.6f m, tilt %.5f rad, "
      "max depth %.5f m, rms speed %.2e m/s, %.3f ms/step, %d recovering steps\n",
      name, r.max_drift, r.top_sag, r.top_creep, r.max_tilt, r.max_depth, r.rms_speed_end,
      r.ms_per_step, r.recovering_steps);
  ::testing::Test::RecordProperty("drift_mm", std::to_string(1e3 * r.max_drift));
  ::testing::Test::RecordProperty("sag_mm", std::to_string(1e3 * r.top_sag));
  ::testing::Test::RecordProperty("ms_per_step", std::to_string(r.ms_per_step));
}

/// The bodies in layers of the given sizes (in spawn order), each layer resting on
/// the one below: its lowest centre at least 0.95 box above the highest centre under
/// it (0.45 above the ground), so no contact sank by more than 5% of a box.
void expectLayers(const std::vector<Watch>& watch, const std::vector<int>& sizes) {
  std::size_t i = 0;
  double below = 0.0;  // the ground's top
  double gap = 0.45 * kBox;
  for (int n : sizes) {
    double lo = 1e9, hi = -1e9;
    for (int k = 0; k < n; ++k, ++i) {
      const double y = double(watch[i].body->getCenterOfMassPosition().y());
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
    EXPECT_GE(lo - below, gap) << "layer ending at body " << i;
    below = hi;
    gap = 0.95 * kBox;
  }
}

class Stacking : public ::testing::TestWithParam<bullet::ContactModel> {};

TEST_P(Stacking, TenBoxTowerStands) {
  BulletWorld w(GetParam());
  w.addGround();
  auto box = boxShape(btVector3(0.5, 0.5, 0.5) * btScalar(kBox));
  std::vector<Watch> watch;
  for (int i = 0; i < 10; ++i) {
    const btVector3 p(0, btScalar((i + 0.5) * kBox + (i + 1) * kGap), 0);
    watch.push_back({w.addBody(box, 1.0, p), p});
  }
  const StackRun r = run(w, watch, watch.back().body, kSeconds);
  report("tower", r);
  EXPECT_LE(r.max_drift, 0.02 * kBox);
  EXPECT_LE(r.top_creep, 0.02 * kBox);
  EXPECT_LE(r.max_tilt, 0.02);
  expectLayers(watch, std::vector<int>(10, 1));
}

/// Five rows of boxes on the ground, each box resting on two: the watched bodies.
std::vector<Watch> addPyramid(BulletWorld& w) {
  w.addGround();
  auto box = boxShape(btVector3(0.5, 0.5, 0.5) * btScalar(kBox));
  std::vector<Watch> watch;
  const double pitch = 1.1 * kBox;  // 10% gaps in a row; each box rests on two
  for (int row = 0; row < 5; ++row) {
    const int n = 5 - row;
    for (int i = 0; i < n; ++i) {
      const btVector3 p(btScalar((i - 0.5 * (n - 1)) * pitch),
                        btScalar((row + 0.5) * kBox + (row + 1) * kGap), 0);
      watch.push_back({w.addBody(box, 1.0, p), p});
    }
  }
  return watch;
}

void expectPyramidStands(const std::vector<Watch>& watch, const StackRun& r) {
  EXPECT_LE(r.max_drift, 0.02 * kBox);
  EXPECT_LE(r.top_creep, 0.02 * kBox);
  EXPECT_LE(r.max_tilt, 0.02);
  expectLayers(watch, {5, 4, 3, 2, 1});
}

TEST_P(Stacking, FifteenBoxPyramidStands) {
  BulletWorld w(GetParam());
  const std::vector<Watch> watch = addPyramid(w);
  const StackRun r = run(w, watch, watch.back().body, kSeconds);
  report("pyramid", r);
  expectPyramidStands(watch, r);
}

// Mix and Free: the potential model's torque from the RPDV acts too (Input has none).
// Its damping part is shared among a body's contacts as the force's is; applied whole
// by each of a box's four contacts, it reversed and grew the boxes' spin every substep
// and the pyramid blew up within a quarter of a second.
class RotationStacking : public ::testing::TestWithParam<RotationMode> {};

TEST_P(RotationStacking, FifteenBoxPyramidStandsWithTheRpdvTorque) {
  BulletWorld w(bullet::ContactModel::Potential);
  bullet::PluginSettings settings = w.plugin->settings();
  settings.query.rotation_mode = GetParam();
  ASSERT_TRUE(w.plugin->setSettings(settings).ok());
  const std::vector<Watch> watch = addPyramid(w);
  const StackRun r = run(w, watch, watch.back().body, kSeconds);
  report(GetParam() == RotationMode::Mix ? "pyramid, mix" : "pyramid, free", r);
  expectPyramidStands(watch, r);
  EXPECT_LE(r.rms_speed_end, 0.05);
}

std::string rotationModeName(const ::testing::TestParamInfo<RotationMode>& mode) {
  return modeName(mode.param);
}

INSTANTIATE_TEST_SUITE_P(Modes, RotationStacking,
                         ::testing::Values(RotationMode::Mix, RotationMode::Free),
                         rotationModeName);

TEST_P(Stacking, MassRatioHundredStackStands) {
  BulletWorld w(GetParam());
  w.addGround();
  auto box = boxShape(btVector3(0.5, 0.5, 0.5) * btScalar(kBox));
  std::vector<Watch> watch;
  // Light, heavy, light, heavy: every contact carries a 1:100 ratio.
  const double masses[] = {1.0, 100.0, 1.0, 100.0};
  for (int i = 0; i < 4; ++i) {
    const btVector3 p(0, btScalar((i + 0.5) * kBox + (i + 1) * kGap), 0);
    watch.push_back({w.addBody(box, masses[i], p), p});
  }
  const StackRun r = run(w, watch, watch.back().body, kSeconds);
  report("mass ratio", r);
  EXPECT_LE(r.max_drift, 0.02 * kBox);
  EXPECT_LE(r.top_creep, 0.02 * kBox);
  EXPECT_LE(r.max_tilt, 0.02);
  // Both models: the rows hold the load at the velocity level (docs/bullet.md); a
  // light box under 100x its weight yields only Bullet's slop and what 100 solver
  // iterations leave unresolved: within 2 mm of the ideal spacing at every contact.
  double below = 0.0;
  for (std::size_t i = 0; i < watch.size(); ++i) {
    const double y = double(watch[i].body->getCenterOfMassPosition().y());
    EXPECT_NEAR(y - below, (i == 0 ? 0.5 : 1.0) * kBox, 2e-3) << "contact under body " << i;
    below = y;
  }
}

INSTANTIATE_TEST_SUITE_P(Models, Stacking, bothContactModels(), contactModelName);

}  // namespace
}  // namespace sc::test
