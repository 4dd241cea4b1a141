// SPDX-License-Identifier: MIT
// Bullet at game rates (60 Hz, and 240 Hz): 0.5 m boxes in a 10-box tower and in
// 1:100 and 1:1000 stacks stand and rest with millimetre overlaps, in every rotation mode
// of the potential model and in the manifold model; a set stiffness is honoured. Overlaps
// are measured here, exactly for boxes (corners inside the other box), never from
// SmartCollision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "bullet_world.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

constexpr double kSize = 0.5;   // box edge [m]
constexpr double kGap = 0.002;  // spawn gap between boxes [m]
constexpr double kSeconds = SC_TEST_SANITIZED ? 2.0 : 10.0;

/// Largest overlap of a column of boxes (each on the one below, the first on the
/// ground), both ways round for each pair.
double columnOverlap(const std::vector<btRigidBody*>& column) {
  double worst = boxCornerDepth(*column[0], nullptr, 0.5 * kSize);
  for (std::size_t i = 1; i < column.size(); ++i) {
    worst = std::max(worst, boxCornerDepth(*column[i], column[i - 1], 0.5 * kSize));
    worst = std::max(worst, boxCornerDepth(*column[i - 1], column[i], 0.5 * kSize));
  }
  return worst;
}

struct ColumnRun {
  double max_overlap_end = 0.0;  ///< largest overlap over the last second [m]
  double sag = 0.0;              ///< ideal top height minus final top height [m]
  double rms_speed = 0.0;        ///< RMS speed of the bodies over the last second [m/s]
  double max_drift = 0.0;        ///< largest horizontal displacement [m]
};

ColumnRun runColumn(BulletWorld& w, const std::vector<btRigidBody*>& column, double seconds) {
  ColumnRun r;
  const int steps = static_cast<int>(std::lround(seconds / w.dt));
  const int last_second = static_cast<int>(std::lround(1.0 / w.dt));
  const ColumnMotion m = stepColumn(w, column, steps, last_second, [&] {
    r.max_overlap_end = std::max(r.max_overlap_end, columnOverlap(column));
  });
  r.rms_speed = m.rms_speed;
  r.max_drift = m.drift;
  const double ideal_top = (double(column.size()) - 0.5) * kSize;
  r.sag = ideal_top - double(column.back()->getCenterOfMassPosition().y());
  return r;
}

std::vector<btRigidBody*> addColumn(BulletWorld& w, const std::vector<double>& masses) {
  w.addGround();
  auto box = boxShape(btVector3(0.5, 0.5, 0.5) * btScalar(kSize));
  std::vector<btRigidBody*> column;
  for (std::size_t i = 0; i < masses.size(); ++i) {
    const double y = (double(i) + 0.5) * kSize + double(i + 1) * kGap;
    column.push_back(w.addBody(box, masses[i], btVector3(0, btScalar(y), 0)));
  }
  return column;
}

void setRotationMode(BulletWorld& w, RotationMode mode) {
  bullet::PluginSettings s = w.plugin->settings();
  s.query.rotation_mode = mode;
  ASSERT_TRUE(w.plugin->setSettings(s).ok());
}

void print(const std::string& name, const ColumnRun& r) {
  std::printf("[%s] overlap %.2f mm, sag %.2f mm, rms speed %.2e m/s, drift %.2f mm\n",
              name.c_str(), 1e3 * r.max_overlap_end, 1e3 * r.sag, r.rms_speed, 1e3 * r.max_drift);
}

// (rate, rotation mode) of the potential model.
class GameRateTower : public ::testing::TestWithParam<std::tuple<double, RotationMode>> {};

TEST_P(GameRateTower, TenBoxesStandAndRest) {
  const auto [hz, mode] = GetParam();
  BulletWorld w(bullet::ContactModel::Potential, -9.81, hz);
  setRotationMode(w, mode);
  const std::vector<btRigidBody*> column = addColumn(w, std::vector<double>(10, 1.0));
  const ColumnRun r = runColumn(w, column, kSeconds);
  print("tower " + std::to_string(int(hz)) + " Hz " + modeName(mode), r);
  EXPECT_LE(r.rms_speed, 0.01);
  EXPECT_LE(r.sag, 0.005);
  EXPECT_LE(r.max_overlap_end, 0.005);
  EXPECT_LE(r.max_drift, 0.01);
}

std::string towerName(const ::testing::TestParamInfo<std::tuple<double, RotationMode>>& p) {
  return std::to_string(int(std::get<0>(p.param))) + "Hz" + modeName(std::get<1>(p.param));
}

INSTANTIATE_TEST_SUITE_P(Rates, GameRateTower,
                         ::testing::Combine(::testing::Values(60.0, 240.0),
                                            ::testing::Values(RotationMode::Input,
                                                              RotationMode::Mix,
                                                              RotationMode::Free)),
                         towerName);

// (rate, contact model, heavy mass) of a light, heavy, light, heavy stack.
class GameRateMassRatio
    : public ::testing::TestWithParam<std::tuple<double, bullet::ContactModel, double>> {};

TEST_P(GameRateMassRatio, StackStandsWithMillimetreOverlaps) {
  const auto [hz, model, heavy] = GetParam();
  BulletWorld w(model, -9.81, hz);
  const std::vector<btRigidBody*> column = addColumn(w, {1.0, heavy, 1.0, heavy});
  const ColumnRun r = runColumn(w, column, kSeconds);
  print("1:" + std::to_string(int(heavy)) + " " + std::to_string(int(hz)) + " Hz " +
            (model == bullet::ContactModel::Potential ? "potential" : "manifold"),
        r);
  EXPECT_LE(r.max_overlap_end, 0.005);
  EXPECT_LE(r.rms_speed, 0.01);
  EXPECT_LE(r.max_drift, 0.01);
}

std::string ratioName(
    const ::testing::TestParamInfo<std::tuple<double, bullet::ContactModel, double>>& p) {
  return std::to_string(int(std::get<0>(p.param))) + "Hz" +
         (std::get<1>(p.param) == bullet::ContactModel::Potential ? "Potential" : "Manifold") +
         "1to" + std::to_string(int(std::get<2>(p.param)));
}

INSTANTIATE_TEST_SUITE_P(Rates, GameRateMassRatio,
                         ::testing::Combine(::testing::Values(60.0, 240.0), bothContactModels(),
                                            ::testing::Values(100.0, 1000.0)),
                         ratioName);

TEST(GameRateSettings, AStiffnessOverrideIsHonouredNotClamped) {
  // 1e5 and 1e7 N/m must give different statics (load / k), not the same clamped one.
  double sag[2] = {0, 0};
  const double k[2] = {1e5, 1e7};
  for (int i = 0; i < 2; ++i) {
    BulletWorld w(bullet::ContactModel::Potential, -9.81, 60.0);
    const std::vector<btRigidBody*> column = addColumn(w, {100.0});
    bullet::ContactSettings c = w.plugin->settings().contact;
    c.contact_stiffness = k[i];
    ASSERT_TRUE(w.plugin->setBodySettings(column[0], c).ok());
    runColumn(w, column, 3.0);
    sag[i] = 0.5 * kSize - double(column[0]->getCenterOfMassPosition().y());
  }
  // 981 N on 1e5 N/m: 9.8 mm; on 1e7 N/m: 0.1 mm.
  EXPECT_NEAR(sag[0], 981.0 / k[0], 0.2 * 981.0 / k[0]);
  EXPECT_NEAR(sag[1], 981.0 / k[1], 2e-4);
  bullet::ContactSettings bad;
  bad.contact_stiffness = -1.0;
  BulletWorld w(bullet::ContactModel::Potential, -9.81, 60.0);
  btRigidBody* b = w.addGround();
  EXPECT_EQ(w.plugin->setBodySettings(b, bad).code(), ErrorCode::InvalidArgument);
  bad.contact_stiffness = std::nan("");
  EXPECT_EQ(w.plugin->setBodySettings(b, bad).code(), ErrorCode::InvalidArgument);
}

// A 1 cm thick closed mesh wall (2 m x 2 m, x in [-0.01, 0]) and a 5 cm projectile at
// 50 and 200 m/s, from eight start phases spread over one step's travel at 60 Hz
// (0.83 m and 3.3 m per step: the shot is sampled far behind the wall).
struct Projectile {
  const char* name;
  double speed;
};

class GameRateProjectile
    : public ::testing::TestWithParam<std::tuple<bullet::ContactModel, Projectile>> {};

TEST_P(GameRateProjectile, StopsAtAThinWallWithoutRebound) {
  const auto [model, shot] = GetParam();
  const std::string kind = shot.name;
  MeshData shot_mesh =
      kind == "cube" ? boxMesh(Vec3(0.025, 0.025, 0.025)) : torusMesh(0.018, 0.007, 16, 8);
  auto shape = bullet::ScBulletShape::create(ModelKind::ClosedPolyhedron, shot_mesh);
  auto wall =
      bullet::ScBulletShape::create(ModelKind::ClosedPolyhedron, boxMesh(Vec3(0.005, 1.0, 1.0)));
  ASSERT_TRUE(shape.ok() && wall.ok());
  const double hz = 60.0;
  int passed = 0;
  double worst_rebound = 0.0;
  for (int phase = 0; phase < 8; ++phase) {
    BulletWorld w(model, 0.0, hz);
    w.addBody(wall.value(), 0.0, btVector3(-0.005, 0, 0));
    const double start = 0.5 + phase * shot.speed * w.dt / 8.0;
    btRigidBody* b = w.addBody(shape.value(), 0.05, btVector3(btScalar(start), 0, 0));
    b->setLinearVelocity(btVector3(btScalar(-shot.speed), 0, 0));
    bool through = false;
    for (int i = 0; i < 60; ++i) {
      w.step();
      // Wholly past the far face (x = -0.01) at any step: it went through.
      through = through || double(b->getCenterOfMassPosition().x()) < -0.01 - 0.025;
    }
    passed += through ? 1 : 0;
    worst_rebound = std::max(worst_rebound, double(b->getLinearVelocity().x()));
    EXPECT_FALSE(through) << "phase " << phase;
    EXPECT_GT(double(b->getCenterOfMassPosition().x()), 0.0) << "phase " << phase;
  }
  std::printf("[projectile %s %.0f m/s %s] %d of 8 through, rebound %.3f m/s\n", shot.name,
              shot.speed, model == bullet::ContactModel::Potential ? "potential" : "manifold",
              passed, worst_rebound);
  EXPECT_LE(worst_rebound, 0.5);
}

std::string projectileName(
    const ::testing::TestParamInfo<std::tuple<bullet::ContactModel, Projectile>>& p) {
  return std::string(std::get<0>(p.param) == bullet::ContactModel::Potential ? "Potential"
                                                                             : "Manifold") +
         std::get<1>(p.param).name + std::to_string(int(std::get<1>(p.param).speed));
}

INSTANTIATE_TEST_SUITE_P(
    Shots, GameRateProjectile,
    ::testing::Combine(bothContactModels(),
                       ::testing::Values(Projectile{"cube", 50.0}, Projectile{"cube", 200.0},
                                         Projectile{"torus", 50.0}, Projectile{"torus", 200.0})),
    projectileName);

}  // namespace
}  // namespace sc::test
