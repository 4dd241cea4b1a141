// SPDX-License-Identifier: MIT
// DirectedResult::status says what a direction's update found: separated, touching,
// penetrating, lagging, beyond the maximum distance, first seen intersecting, or not
// computed; each case reached through PairTracker on two unit cubes along x.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "smartcollision/collision.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

class DirectionStatusTest : public ::testing::Test {
 protected:
  ModelPtr cube = [] {
    auto piece = buildPiece(ModelKind::ClosedPolyhedron, boxMesh(Vec3::Constant(0.5)));
    EXPECT_TRUE(piece.ok());
    return std::make_shared<Model>(ModelKind::ClosedPolyhedron,
                                   std::vector<PiecePtr>{piece.value()});
  }();
  Part a{cube.get(), Rigid(), 1}, b{cube.get(), Rigid(), 2};
  SceneSettings settings;
  PairTracker tracker;

  /// The target cube at x (the opponent at the origin): its faces are x - 1 apart.
  DirectedResult at(double x, double y_turn = 0.0) {
    Placement p;
    p.world_center = Vec3(x, 0, 0);
    p.orientation = Quat(Eigen::AngleAxisd(y_turn, Vec3::UnitZ()));
    DirectedResult out[2];
    tracker.update({&a, 1, p}, {&b, 1, Placement()}, {true, false}, settings, out);
    return out[0];
  }
};

TEST_F(DirectionStatusTest, SeparatedTouchingAndPenetratingAreToldApart) {
  EXPECT_EQ(at(1.5).status, DirectionStatus::Separated);
  const DirectedResult near = at(1.0 + 0.5 * settings.tolerance);
  EXPECT_EQ(near.status, DirectionStatus::Touching);
  EXPECT_GT(near.distance, 0.0);
  // Faces flush: distance 0 reads as penetrating(), but there is no depth.
  const DirectedResult flush = at(1.0);
  EXPECT_EQ(flush.status, DirectionStatus::Touching);
  EXPECT_TRUE(flush.penetrating());
  EXPECT_FALSE(flush.hasDepth());
  EXPECT_TRUE(flush.tpdv.isZero(0.0));
  const DirectedResult deep = at(0.9);
  EXPECT_EQ(deep.status, DirectionStatus::Penetrating);
  EXPECT_TRUE(deep.hasDepth());
  EXPECT_NEAR(deep.tpdv.norm(), 0.1, settings.tolerance);
  EXPECT_EQ(at(1.5).status, DirectionStatus::Separated);  // and out again
}

TEST_F(DirectionStatusTest, BeyondTheMaximumDistance) {
  settings.max_distance = 0.2;
  EXPECT_EQ(at(1.5).code, ErrorCode::NoResult);
  EXPECT_EQ(at(1.5).status, DirectionStatus::BeyondMaxDistance);
  EXPECT_EQ(at(1.1).status, DirectionStatus::Separated);
}

TEST_F(DirectionStatusTest, FirstSeenIntersectingAndNotComputed) {
  const DirectedResult first = at(0.5);
  EXPECT_EQ(first.code, ErrorCode::InvalidInitialTransformation);
  EXPECT_EQ(first.status, DirectionStatus::FirstSeenIntersecting);
  settings.tolerance = -1.0;  // refused: nothing computed
  const DirectedResult refused = at(1.5);
  EXPECT_EQ(refused.code, ErrorCode::InvalidArgument);
  EXPECT_EQ(refused.status, DirectionStatus::NotComputed);
}

// One iteration cannot settle a proxy that must slide round a turned corner on its
// way in: the depth is reported as lagging, and settles on the next updates.
TEST_F(DirectionStatusTest, AProxyOutOfIterationsLags) {
  settings.max_iterations = 1;
  ASSERT_EQ(at(1.5).status, DirectionStatus::Separated);
  const DirectedResult in = at(0.6, 0.4);
  ASSERT_TRUE(in.hasDepth());
  EXPECT_EQ(in.status, DirectionStatus::Lagging);
  settings.max_iterations = 30;
  DirectedResult settled = at(0.6, 0.4);
  for (int i = 0; i < 5 && settled.status == DirectionStatus::Lagging; ++i) settled = at(0.6, 0.4);
  EXPECT_EQ(settled.status, DirectionStatus::Penetrating);
}

}  // namespace
}  // namespace sc::test
