// SPDX-License-Identifier: MIT
// Scene set-up: the meshes of the block, the cup and the peg, the bodies, and the
// held tool's contact settings.
#include "scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "../common/cli.h"
#include "sc_support/off_mesh.h"

namespace sc::demo::haptic {
namespace {

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "%s\n", what.c_str());
  std::exit(1);
}

sc::MeshData boxMesh(const Vec3& h) {
  sc::MeshData m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z());
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

/// Ring of four corners (x, z) = (+-a, +-a) at height y, counter-clockwise seen from +y.
void addRing(sc::MeshData& m, double a, double y) {
  m.vertices.emplace_back(-a, y, -a);
  m.vertices.emplace_back(-a, y, a);
  m.vertices.emplace_back(a, y, a);
  m.vertices.emplace_back(a, y, -a);
}

/// Triangle (a, b, c) wound so that its normal points along `out`.
void addFacing(sc::MeshData& m, int a, int b, int c, const Vec3& out) {
  const Vec3& pa = m.vertices[std::size_t(a)];
  const Vec3 n = (m.vertices[std::size_t(b)] - pa).cross(m.vertices[std::size_t(c)] - pa);
  if (n.dot(out) >= 0.0)
    m.triangles.emplace_back(a, b, c);
  else
    m.triangles.emplace_back(a, c, b);
}

/// Quad strip between rings r0 and r1 (4 vertices each). Horizontal strips face
/// `facing` = +1 (up) or -1 (down); walls face away from the y axis (`facing` = 0)
/// or towards it (`facing` = 2, the hole's walls).
void joinRings(sc::MeshData& m, int r0, int r1, int facing) {
  for (int i = 0; i < 4; ++i) {
    const int a = r0 + i, b = r0 + (i + 1) % 4, c = r1 + (i + 1) % 4, d = r1 + i;
    Vec3 out;
    if (facing == 1 || facing == -1) {
      out = Vec3(0, facing, 0);
    } else {
      const Vec3 mid = 0.25 * (m.vertices[std::size_t(a)] + m.vertices[std::size_t(b)] +
                               m.vertices[std::size_t(c)] + m.vertices[std::size_t(d)]);
      out = Vec3(mid.x(), 0, mid.z()) * (facing == 2 ? -1.0 : 1.0);
    }
    addFacing(m, a, b, c, out);
    addFacing(m, a, c, d, out);
  }
}

/// A square block (half width `outer`, from y = 0 to `height`) with a square hole of
/// half width `hole` along y: a through-hole when `floor` is 0, else a pocket with a
/// floor of that thickness. One closed (genus 1 or 0) non-convex polyhedron.
sc::MeshData holedBlock(double outer, double hole, double height, double floor) {
  sc::MeshData m;
  addRing(m, outer, height);  // 0: outer top
  addRing(m, hole, height);   // 4: hole top
  addRing(m, hole, floor);    // 8: hole bottom (or pocket floor)
  addRing(m, outer, 0.0);     // 12: outer bottom
  joinRings(m, 0, 4, 1);      // top face between the rings
  joinRings(m, 4, 8, 2);      // hole walls
  joinRings(m, 12, 0, 0);     // outer walls
  if (floor <= 0.0) {
    joinRings(m, 8, 12, -1);  // bottom face between the rings
  } else {
    addFacing(m, 8, 9, 10, Vec3(0, 1, 0));  // pocket floor
    addFacing(m, 8, 10, 11, Vec3(0, 1, 0));
    addFacing(m, 12, 13, 14, Vec3(0, -1, 0));  // outer bottom
    addFacing(m, 12, 14, 15, Vec3(0, -1, 0));
  }
  return m;
}

DrawMesh drawMeshOf(const sc::bullet::ScBulletShape& shape) {
  DrawMesh m;
  for (const btVector3& v : shape.vertices())
    m.vertices.insert(m.vertices.end(), {float(v.x()), float(v.y()), float(v.z())});
  m.indices = shape.indices();
  return m;
}

}  // namespace

HapticScene::HapticScene(const std::string& scene, double physics_dt)
    : cavity_(scene == "cavity"), physics_dt_(physics_dt) {
  bullet_.makeSmartCollision({});
  bullet_.world->setGravity(btVector3(0, -9.81f, 0));
  if (cavity_)
    buildCavity();
  else
    buildPeg();
}

HapticScene::~HapticScene() {
  for (auto& b : rigid_) bullet_.world->removeRigidBody(b.get());
}

sc::haptics::CouplingPose HapticScene::bodyTarget(const sc::haptics::CouplingPose& device) const {
  sc::haptics::CouplingPose t;
  t.position = device.position + device.orientation * grip_position_;
  t.orientation = (device.orientation * grip_rotation_).normalized();
  return t;
}

Vec3 HapticScene::meshRotationVector(const sc::haptics::BodyState& s) const {
  return sc::haptics::rotationVector(s.pose.orientation * grip_rotation_.conjugate());
}

double HapticScene::insertedDepth(const sc::haptics::BodyState& s) const {
  return block_top_ - (s.pose.position.y() - tool_half_.y());
}

/// Peg: centre within the hole's clearance (+1 mm), at least 20 mm below the top.
/// Cavity: the tool's box within the pocket's walls and below its rim.
bool HapticScene::inside(const sc::haptics::BodyState& s) const {
  const double lateral = std::max(std::abs(s.pose.position.x()), std::abs(s.pose.position.z()));
  if (cavity_)
    return lateral + std::max(tool_half_.x(), tool_half_.z()) <= hole_half_ + 0.002 &&
           s.pose.position.y() + tool_half_.y() <= block_top_ + 0.02 && insertedDepth(s) > 0.04;
  return lateral <= hole_half_ - tool_half_.x() + 0.001 && insertedDepth(s) >= 0.02;
}

std::shared_ptr<sc::bullet::ScBulletShape> HapticScene::makeShape(const sc::MeshData& mesh,
                                                                  sc::ModelKind kind) {
  sc::bullet::ShapeOptions options;
  options.aabb_margin = 0.005;
  auto s = sc::bullet::ScBulletShape::create(kind, mesh, options);
  if (!s.ok()) {
    std::fprintf(stderr, "shape: %s\n", s.status().message().c_str());
    return nullptr;
  }
  shapes_.push_back(s.value());
  return s.value();
}

/// A body whose input mesh frame is at `world_from_mesh`.
btRigidBody* HapticScene::addRigid(const sc::bullet::ScBulletShape& shape, double mass,
                                   const btTransform& world_from_mesh) {
  btVector3 inertia(0, 0, 0);
  if (mass > 0) shape.calculateLocalInertia(btScalar(mass), inertia);
  btRigidBody::btRigidBodyConstructionInfo ci(
      btScalar(mass), nullptr, const_cast<sc::bullet::ScBulletShape*>(&shape), inertia);
  ci.m_startWorldTransform = world_from_mesh * shape.meshFromShape();
  rigid_.push_back(std::make_unique<btRigidBody>(ci));
  btRigidBody* b = rigid_.back().get();
  b->setActivationState(DISABLE_DEACTIVATION);
  bullet_.world->addRigidBody(b);
  return b;
}

/// The held tool: no gravity (the device carries it), coupled to the device.
void HapticScene::setTool(btRigidBody* body, const sc::bullet::ScBulletShape& shape) {
  tool_ = body;
  const btTransform& g = shape.meshFromShape();
  grip_position_ =
      Vec3(double(g.getOrigin().x()), double(g.getOrigin().y()), double(g.getOrigin().z()));
  const btQuaternion q = g.getRotation();
  grip_rotation_ = Quat(double(q.w()), double(q.x()), double(q.y()), double(q.z())).normalized();
  tool_->setFlags(tool_->getFlags() | BT_DISABLE_WORLD_GRAVITY);
  tool_->setGravity(btVector3(0, 0, 0));
  // The hand-held body's contacts are springs of a period of 10 physics steps
  // (kT = m omega^2), not the default rigid rows: the coupling's force-continuity
  // bound (docs/haptics.md) assumes a contact stops the body over several steps.
  sc::bullet::ContactSettings soft = bullet_.world->plugin().settings().contact;
  const double omega = 2.0 * kPi / (soft.contact_period_steps * physics_dt_);
  soft.contact_stiffness = double(1.0 / tool_->getInvMass()) * omega * omega;
  if (!bullet_.world->plugin().setBodySettings(tool_, soft).ok()) fail("setBodySettings");
}

void HapticScene::buildCommon() {
  auto cube = makeShape(boxMesh(Vec3(1, 1, 1)), sc::ModelKind::ClosedPolyhedron);
  cube_mesh_ = drawMeshOf(*cube);
}

/// The fixed block: half width 100 mm, a square hole of half width `hole_half` along y
/// from its top at `top`, through (`floor` 0) or a pocket above a floor that thick.
void HapticScene::addBlock(double hole_half, double top, double floor, const char* what) {
  hole_half_ = hole_half;
  block_top_ = top;
  auto block =
      makeShape(holedBlock(0.1, hole_half_, block_top_, floor), sc::ModelKind::ClosedPolyhedron);
  if (!block) fail(std::string(what) + ": not a valid closed polyhedron");
  fixed_ = addRigid(*block, 0.0, btTransform::getIdentity());
  fixed_mesh_ = drawMeshOf(*block);
  fixed_triangles_ = block->indices().size() / 3;
}

/// The held tool, 0.5 kg, its mesh frame at `home`.
void HapticScene::addTool(const sc::bullet::ScBulletShape& shape, const Vec3& home) {
  tool_home_ = home;
  const btVector3 at(btScalar(home.x()), btScalar(home.y()), btScalar(home.z()));
  setTool(addRigid(shape, 0.5, btTransform(btQuaternion::getIdentity(), at)), shape);
  tool_mesh_ = drawMeshOf(shape);
  tool_triangles_ = shape.indices().size() / 3;
}

// Peg scene: block 200 x 80 x 200 mm with a 50 mm square through-hole, top at
// y = 80 mm; peg 46 x 120 x 46 mm.
void HapticScene::buildPeg() {
  buildCommon();
  addBlock(0.025, 0.08, 0.0, "holed block");
  tool_half_ = Vec3(0.023, 0.06, 0.023);
  auto peg = makeShape(boxMesh(tool_half_), sc::ModelKind::ClosedPolyhedron);
  addTool(*peg, Vec3(0, 0.17, 0));
}

// Cavity scene: a cup 200 x 120 x 200 mm with a 140 mm square pocket 80 mm deep;
// the bunny (bunny00.off, 75k triangles) scaled to 100 mm.
void HapticScene::buildCavity() {
  buildCommon();
  addBlock(0.07, 0.12, 0.04, "cup");
  const std::string bunny_file = demoMesh("bunny00.off");
  sc::MeshData bunny = sc::support::readOffOrEmpty(bunny_file);
  if (bunny.triangles.empty()) fail("cannot read " + bunny_file + " (run scripts/setup.sh)");
  bunny = sc::support::fitToSize(std::move(bunny), 0.1);
  auto tool = makeShape(bunny, sc::ModelKind::ClosedPolyhedron);
  if (!tool) tool = makeShape(bunny, sc::ModelKind::TriangleSoup);
  if (!tool) fail("bunny: cannot build the model");
  btVector3 lo, hi;
  tool->getAabb(btTransform::getIdentity(), lo, hi);
  tool_half_ = Vec3(0.5 * double(hi.x() - lo.x()), 0.5 * double(hi.y() - lo.y()),
                    0.5 * double(hi.z() - lo.z())) -
               Vec3::Constant(tool->aabbMargin());
  addTool(*tool, Vec3(0, 0.2, 0));
  tool_color_[0] = 0.85f;
  tool_color_[1] = 0.7f;
  tool_color_[2] = 0.45f;
}

}  // namespace sc::demo::haptic
