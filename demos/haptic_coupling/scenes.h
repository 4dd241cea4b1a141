// SPDX-License-Identifier: MIT
// The demo's Bullet world and its two bodies: a fixed block and the hand-held tool.
// `peg`: a square peg into a block with a square through-hole (2 mm clearance per
// side); `cavity`: the bunny (75k triangles) into a cup's pocket.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "../common/bullet_world.h"
#include "../common/viewer.h"
#include "smartcollision/bullet/bullet.h"
#include "smartcollision/haptics/virtual_coupling.h"

namespace sc::demo::haptic {

class HapticScene {
 public:
  /// Builds `scene` ("peg" or "cavity") for physics steps of `physics_dt`; exits with
  /// a message when a body cannot be built.
  HapticScene(const std::string& scene, double physics_dt);
  ~HapticScene();
  HapticScene(const HapticScene&) = delete;
  HapticScene& operator=(const HapticScene&) = delete;

  sc::bullet::ScDynamicsWorld& world() { return *bullet_.world; }
  btRigidBody& tool() { return *tool_; }
  const btRigidBody& tool() const { return *tool_; }
  const btRigidBody& fixed() const { return *fixed_; }

  /// The tool's mesh frame at the start.
  const Vec3& toolHome() const { return tool_home_; }
  /// The body's pose that holds the tool's mesh frame at the device's pose.
  sc::haptics::CouplingPose bodyTarget(const sc::haptics::CouplingPose& device) const;
  /// The tool's rotation vector in its mesh frame.
  Vec3 meshRotationVector(const sc::haptics::BodyState& s) const;
  /// How far the tool's lowest point is below the top of the block [m].
  double insertedDepth(const sc::haptics::BodyState& s) const;
  /// Whether the task is done: the tool in the hole or the pocket.
  bool inside(const sc::haptics::BodyState& s) const;

  std::size_t toolTriangles() const { return tool_triangles_; }
  std::size_t fixedTriangles() const { return fixed_triangles_; }
  const DrawMesh& toolMesh() const { return tool_mesh_; }
  const DrawMesh& fixedMesh() const { return fixed_mesh_; }
  const DrawMesh& cubeMesh() const { return cube_mesh_; }
  const float* toolColor() const { return tool_color_; }
  const float* fixedColor() const { return fixed_color_; }

 private:
  std::shared_ptr<sc::bullet::ScBulletShape> makeShape(const sc::MeshData& mesh,
                                                       sc::ModelKind kind);
  btRigidBody* addRigid(const sc::bullet::ScBulletShape& shape, double mass,
                        const btTransform& world_from_mesh);
  void setTool(btRigidBody* body, const sc::bullet::ScBulletShape& shape);
  void addBlock(double hole_half, double top, double floor, const char* what);
  void addTool(const sc::bullet::ScBulletShape& shape, const Vec3& home);
  void buildCommon();
  void buildPeg();
  void buildCavity();

  bool cavity_;
  double physics_dt_;
  sc::demo::BulletWorld<sc::bullet::ScDynamicsWorld> bullet_;
  std::vector<std::shared_ptr<sc::bullet::ScBulletShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> rigid_;
  btRigidBody* tool_ = nullptr;
  btRigidBody* fixed_ = nullptr;
  DrawMesh tool_mesh_, fixed_mesh_, cube_mesh_;
  float tool_color_[3] = {0.85f, 0.45f, 0.25f};
  float fixed_color_[3] = {0.45f, 0.55f, 0.75f};
  std::size_t tool_triangles_ = 0, fixed_triangles_ = 0;
  Vec3 tool_half_ = Vec3::Zero();
  Vec3 tool_home_ = Vec3::Zero();
  Vec3 grip_position_ = Vec3::Zero();  ///< the tool's shape frame in its mesh frame
  Quat grip_rotation_ = Quat::Identity();
  double hole_half_ = 0.0, block_top_ = 0.0;
};

}  // namespace sc::demo::haptic
