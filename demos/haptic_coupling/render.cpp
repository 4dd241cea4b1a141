// SPDX-License-Identifier: MIT
#include "render.h"

#include <cstdio>
#include <cstring>

namespace sc::demo::haptic {
namespace {

DrawItem drawItem(const DrawMesh* mesh, const btTransform& t, const float* color, float scale) {
  DrawItem item;
  item.mesh = mesh;
  btScalar m[16];
  t.getOpenGLMatrix(m);
  for (int i = 0; i < 16; ++i) item.matrix[i] = float(m[i]) * (i < 12 && i % 4 < 3 ? scale : 1.0f);
  std::memcpy(item.color, color, sizeof(item.color));
  return item;
}

/// The unit cube stretched to a 0.6 x 0.02 x 0.6 m slab just below y = 0.
DrawItem ground(const DrawMesh* cube) {
  const float color[3] = {0.55f, 0.6f, 0.65f};
  DrawItem g = drawItem(cube, btTransform(btQuaternion::getIdentity(), btVector3(0, -0.01f, 0)),
                        color, 1.0f);
  g.matrix[0] = 0.3f;
  g.matrix[5] = 0.01f;
  g.matrix[10] = 0.3f;
  return g;
}

}  // namespace

void Renderer::collect(std::vector<DrawItem>& items) {
  ++frames_;
  items.push_back(ground(&scene_.cubeMesh()));
  items.push_back(
      drawItem(&scene_.fixedMesh(), scene_.fixed().getWorldTransform(), scene_.fixedColor(), 1.0f));
  const sc::haptics::BodyState s = stateOf(loops_.bodyState());
  const btTransform body(
      btQuaternion(btScalar(s.pose.orientation.x()), btScalar(s.pose.orientation.y()),
                   btScalar(s.pose.orientation.z()), btScalar(s.pose.orientation.w())),
      btVector3(btScalar(s.pose.position.x()), btScalar(s.pose.position.y()),
                btScalar(s.pose.position.z())));
  items.push_back(drawItem(&scene_.toolMesh(), body, scene_.toolColor(), 1.0f));
  const PoseWords d = loops_.devicePose();
  const float ghost[3] = {0.2f, 0.75f, 0.3f};
  items.push_back(drawItem(
      &scene_.cubeMesh(),
      btTransform(btQuaternion(btScalar(d[4]), btScalar(d[5]), btScalar(d[6]), btScalar(d[3])),
                  btVector3(btScalar(d[0]), btScalar(d[1]), btScalar(d[2]))),
      ghost, 0.006f));
}

std::string Renderer::overlay() {
  const LoopMetrics& m = loops_.metrics();
  const bool finished = !loops_.running() && m.elapsed > 0.0;
  const auto now = Clock::now();
  const double dt = std::chrono::duration<double>(now - rate_time_).count();
  if (finished) {  // a finished headless run: its mean rates
    haptic_rate_ = double(m.haptic_count.load()) / m.elapsed;
    physics_rate_ = double(m.physics_count.load()) / m.elapsed;
    frame_rate_ = 0.0;
  } else if (dt >= 0.5) {
    const long h = m.haptic_count.load(), p = m.physics_count.load(), f = frames_;
    haptic_rate_ = double(h - rate_haptic_) / dt;
    physics_rate_ = double(p - rate_physics_) / dt;
    frame_rate_ = double(f - rate_frames_) / dt;
    rate_haptic_ = h;
    rate_physics_ = p;
    rate_frames_ = f;
    rate_time_ = now;
  }
  char fps[32];
  std::snprintf(fps, sizeof(fps), "%.0f fps", frame_rate_);
  const std::string graphics = finished ? std::string("(headless run)") : std::string(fps);
  char buf[768];
  std::snprintf(
      buf, sizeof(buf),
      "scene %s   device %s\n"
      "haptic %.0f Hz   physics %.0f Hz   graphics %s\n"
      "coupling force %.1f N (max %.0f N)   max depth %.2f mm   energy generated %.2e J\n%s",
      scene_name_.c_str(), loops_.device().name(), haptic_rate_, physics_rate_, graphics.c_str(),
      m.last_force.load(), loops_.coupling().gains().max_force, 1e3 * m.max_depth.load(),
      m.generated.load(), loops_.device().status().c_str());
  return buf;
}

}  // namespace sc::demo::haptic
