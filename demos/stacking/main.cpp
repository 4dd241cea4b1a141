// SPDX-License-Identifier: MIT
// Stacking demo: Bullet rigid bodies with SmartCollision contacts (potential or
// manifold model, switchable with 'm'): a tower, a pyramid, a 1:100 mass-ratio stack
// and real meshes resting on each other, or a pile of meshes in a box. --headless runs
// a fixed time and writes a PNG and JSON metrics.
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "../common/bullet_world.h"
#include "../common/cli.h"
#include "../common/knot_pile.h"
#include "../common/viewer.h"
#include "sc_support/off_mesh.h"
#include "smartcollision/bullet/bullet.h"

namespace {

using sc::bullet::ContactModel;


struct Options : sc::demo::HeadlessOptions {
  Options() { seconds = 10.0; }
  std::string scene = "tower";
  ContactModel model = ContactModel::Potential;
  sc::RotationMode rotation = sc::bullet::defaultQuerySettings().rotation_mode;
  long steps = 0;  ///< when > 0, overrides seconds (soak runs: bench/soak.sh)
  double hz = 240.0;  ///< physics rate (one substep per step)
  unsigned seed = 7;  ///< the pile's random turns
  std::vector<std::string> meshes;
};

struct Body {
  btRigidBody* body = nullptr;
  const sc::demo::DrawMesh* mesh = nullptr;
  btVector3 start;
  btVector3 scale = btVector3(1, 1, 1);  ///< drawn mesh scaled (walls of the pile's box)
  float color[3] = {0.8f, 0.5f, 0.3f};
};

sc::demo::DrawMesh drawMeshOf(const sc::bullet::ScBulletShape& shape) {
  sc::demo::DrawMesh m;
  for (const btVector3& v : shape.vertices()) m.vertices.insert(m.vertices.end(), {float(v.x()), float(v.y()), float(v.z())});
  m.indices = shape.indices();
  return m;
}

sc::demo::DrawMesh drawMeshOf(const sc::MeshData& mesh) {
  sc::demo::DrawMesh m;
  for (const sc::Vec3& v : mesh.vertices) m.vertices.insert(m.vertices.end(), {float(v.x()), float(v.y()), float(v.z())});
  for (const sc::Tri& t : mesh.triangles) m.indices.insert(m.indices.end(), {t[0], t[1], t[2]});
  return m;
}

bool finite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

sc::MeshData boxMesh(double h) {
  sc::MeshData m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

class Demo {
 public:
  explicit Demo(const Options& o) : options_(o) { build(); }
  ~Demo() { clear(); }

  void build() {
    clear();
    sc::bullet::PluginSettings settings;
    settings.model = options_.model;
    settings.query.rotation_mode = options_.rotation;
    // StackingSolver: the mass-ratio scene stands at 60 Hz.
    bullet_.makeSmartCollision(settings, std::make_unique<sc::bullet::StackingSolver>());
    bullet_.world->setGravity(btVector3(0, -9.81f, 0));
    ground_shape_ = std::make_unique<btBoxShape>(btVector3(10, 1, 10));
    ground_mesh_ = drawMeshOf(*makeShape(boxMesh(1.0)));  // drawn scaled below
    addRigid(ground_shape_.get(), 0.0, btVector3(0, -1, 0));
    box_ = makeShape(boxMesh(0.5));
    box_mesh_ = drawMeshOf(*box_);
    if (options_.scene == "pyramid") {
      for (int row = 0; row < 5; ++row)
        for (int i = 0; i < 5 - row; ++i) addBox(btVector3(btScalar((i - 0.5 * (4 - row)) * 1.1), btScalar(row + 0.5 + (row + 1) * 0.01), 0), 1.0);
    } else if (options_.scene == "massratio") {
      const double masses[] = {1.0, 100.0, 1.0, 100.0};
      for (int i = 0; i < 4; ++i) addBox(btVector3(0, btScalar(i + 0.5 + (i + 1) * 0.01), 0), masses[i]);
    } else if (options_.scene == "meshes") {
      addMeshes();
    } else if (options_.scene == "pile") {
      addPile();
    } else {
      for (int i = 0; i < 10; ++i) addBox(btVector3(0, btScalar(i + 0.5 + (i + 1) * 0.01), 0), 1.0);
    }
    steps_ = 0;
    non_finite_steps_ = 0;
    step_seconds_ = 0.0;
    max_depth_ = 0.0;
    max_drift_ = 0.0;
  }

  void step() {
    const auto t0 = std::chrono::steady_clock::now();
    bullet_.world->stepSimulation(btScalar(1.0 / options_.hz), 1, btScalar(1.0 / options_.hz));
    step_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++steps_;
    max_depth_ = std::max(max_depth_, bullet_.world->plugin().stats().max_depth);
    trackSoakMetrics();
    const Body& top = bodies_.back();
    const btVector3 d = top.body->getCenterOfMassPosition() - top.start;
    max_drift_ = std::max(max_drift_, std::sqrt(double(d.x() * d.x() + d.z() * d.z())));
    // RMS velocity over the last second of a fixed run ("at rest").
    if (options_.headless && steps_ > static_cast<long>((options_.seconds - 1.0) * options_.hz)) {
      double s2 = 0;
      for (const Body& b : bodies_) s2 += double(b.body->getLinearVelocity().length2());
      rest_sum_ += s2 / double(bodies_.size());
      ++rest_samples_;
    }
  }

  /// What a long run must not show: non-finite states, energy gained, memory growth.
  void trackSoakMetrics() {
    bool ok = true;
    for (const Body& b : bodies_)
      ok = ok && finite(b.body->getCenterOfMassPosition()) && finite(b.body->getLinearVelocity()) &&
           finite(b.body->getAngularVelocity());
    if (!ok) ++non_finite_steps_;
    const double e = energy();
    if (steps_ == 1) start_energy_ = max_energy_ = e;
    max_energy_ = std::max(max_energy_, e);
    if (steps_ == static_cast<long>(options_.hz)) rss_after_1s_kb_ = sc::demo::residentKb();
  }

  void toggleModel() {
    options_.model = options_.model == ContactModel::Potential ? ContactModel::Manifold : ContactModel::Potential;
    bullet_.world->plugin().setContactModel(options_.model);
  }
  void setScene(const std::string& s) {
    options_.scene = s;
    build();
  }

  void collect(std::vector<sc::demo::DrawItem>& items) const {
    btTransform t(btQuaternion::getIdentity(), btVector3(0, -0.5f, 0));
    btScalar m[16];
    t.getOpenGLMatrix(m);
    const float ground_color[3] = {0.55f, 0.6f, 0.65f};
    sc::demo::DrawItem ground = sc::demo::drawItem(&ground_mesh_, m, ground_color);
    // the ground mesh is a 2 m cube: stretch it to 20 x 1 x 20 m
    ground.matrix[0] = 10;
    ground.matrix[5] = 0.5f;
    ground.matrix[10] = 10;
    items.push_back(ground);
    std::vector<const Body*> drawn;
    if (base_.body != nullptr) drawn.push_back(&base_);
    for (const Body& b : walls_) drawn.push_back(&b);
    for (const Body& b : bodies_) drawn.push_back(&b);
    for (const Body* bp : drawn) {
      const Body& b = *bp;
      b.body->getWorldTransform().getOpenGLMatrix(m);
      sc::demo::DrawItem item = sc::demo::drawItem(b.mesh, m, b.color);
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 4; ++r) item.matrix[4 * c + r] *= float(b.scale[c]);
      items.push_back(item);
    }
  }

  std::string overlay() const {
    return sc::demo::overlayText(
        "scene %s (1 tower, 2 pyramid, 3 mass ratio, 4 meshes, 5 pile; r reset)\n"
        "model %s (m switches)   t = %.2f s   %.3f ms/step\n"
        "top drift %.4f m   max penetration %.4f m",
        options_.scene.c_str(),
        options_.model == ContactModel::Potential ? "potential" : "manifold", steps_ / options_.hz,
        steps_ ? 1e3 * step_seconds_ / steps_ : 0.0, max_drift_, max_depth_);
  }

  double energy() const {
    double e = 0.0;
    for (const Body& b : bodies_) {
      const double m = 1.0 / double(b.body->getInvMass());
      e += 0.5 * m * double(b.body->getLinearVelocity().length2()) + m * 9.81 * double(b.body->getCenterOfMassPosition().y());
      const btVector3 w = b.body->getWorldTransform().getBasis().transpose() * b.body->getAngularVelocity();
      const btVector3 inv = b.body->getInvInertiaDiagLocal();
      for (int k = 0; k < 3; ++k) e += inv[k] > 0 ? 0.5 * double(w[k] * w[k] / inv[k]) : 0.0;
    }
    return e;
  }

  std::string json() const {
    char buf[2048];
    std::snprintf(buf, sizeof(buf),
                  "{\n  \"scene\": \"%s\",\n  \"model\": \"%s\",\n  \"bodies\": %zu,\n  \"hz\": %.0f,\n"
                  "  \"steps\": %ld,\n  \"seconds\": %.3f,\n  \"top_drift_m\": %.6f,\n  \"max_penetration_m\": %.6f,\n"
                  "  \"rms_velocity_at_rest_mps\": %.6g,\n  \"energy_J\": %.6f,\n  \"ms_per_step\": %.4f,\n"
                  "  \"non_finite_steps\": %ld,\n  \"max_energy_rise_J\": %.6g,\n"
                  "  \"rss_after_1s_kB\": %ld,\n  \"rss_end_kB\": %ld,\n  \"peak_rss_kB\": %ld\n}\n",
                  options_.scene.c_str(), options_.model == ContactModel::Potential ? "potential" : "manifold",
                  bodies_.size(), options_.hz, steps_, steps_ / options_.hz, max_drift_, max_depth_,
                  rest_samples_ ? std::sqrt(rest_sum_ / rest_samples_) : 0.0, energy(),
                  steps_ ? 1e3 * step_seconds_ / steps_ : 0.0, non_finite_steps_, max_energy_ - start_energy_,
                  rss_after_1s_kb_, sc::demo::residentKb(),
                  std::max(sc::demo::peakResidentKb(), sc::demo::residentKb()));
    return buf;
  }

  float targetY() const { return options_.scene == "tower" ? 5.0f : options_.scene == "pile" ? 0.6f : 1.5f; }
  float distance() const { return options_.scene == "tower" ? 19.0f : options_.scene == "meshes" || options_.scene == "pile" ? 7.0f : 10.0f; }

 private:
  std::shared_ptr<sc::bullet::ScBulletShape> makeShape(const sc::MeshData& mesh) {
    auto s = sc::bullet::ScBulletShape::create(sc::ModelKind::ClosedPolyhedron, mesh);
    if (!s.ok()) {
      std::fprintf(stderr, "shape: %s\n", s.status().message().c_str());
      return nullptr;
    }
    shapes_.push_back(s.value());
    return s.value();
  }

  btRigidBody* addRigid(btCollisionShape* shape, double mass, const btVector3& p) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(btScalar(mass), inertia);
    btRigidBody::btRigidBodyConstructionInfo ci(btScalar(mass), nullptr, shape, inertia);
    ci.m_startWorldTransform.setOrigin(p);
    rigid_.push_back(std::make_unique<btRigidBody>(ci));
    btRigidBody* b = rigid_.back().get();
    b->setActivationState(DISABLE_DEACTIVATION);  // metrics see the contact model, not sleep
    bullet_.world->addRigidBody(b);
    return b;
  }

  void addBox(const btVector3& p, double mass) {
    Body b;
    b.body = addRigid(box_.get(), mass, p);
    b.mesh = &box_mesh_;
    b.start = p;
    const float shade = mass > 10 ? 0.35f : 0.0f;
    const float palette[3][3] = {{0.85f, 0.45f, 0.25f}, {0.3f, 0.55f, 0.8f}, {0.45f, 0.7f, 0.35f}};
    const float* c = palette[bodies_.size() % 3];
    for (int k = 0; k < 3; ++k) b.color[k] = c[k] - shade * c[k];
    bodies_.push_back(b);
  }

  /// A 3 m x 3 m box of walls 1.2 m high (Bullet boxes: primitives stay primitives)
  /// and 24 non-convex bodies of 0.5 m dropped into it in layers, turned at random:
  /// CGAL's knots, or the --mesh files taken in turn (docs/bullet.md).
  void addPile() {
    for (const sc::demo::PileWall& w : sc::demo::pileWalls()) {
      wall_shapes_.push_back(std::make_unique<btBoxShape>(w.half_extents));
      wall_draw_.push_back(std::make_unique<sc::demo::DrawMesh>(drawMeshOf(boxMesh(1.0))));
      Body b;
      b.body = addRigid(wall_shapes_.back().get(), 0.0, w.center);
      b.mesh = wall_draw_.back().get();
      b.scale = w.half_extents;
      b.color[0] = b.color[1] = b.color[2] = 0.6f;
      walls_.push_back(b);
    }
    std::vector<std::string> paths = options_.meshes;
    if (paths.empty()) paths.push_back(sc::demo::demoMesh("knot1.off"));
    std::vector<std::shared_ptr<sc::bullet::ScBulletShape>> kinds;
    for (const std::string& path : paths) {
      sc::MeshData mesh = sc::support::readOffOrEmpty(path);
      auto shape = mesh.triangles.empty() ? nullptr
                                          : makeShape(sc::support::fitToSize(std::move(mesh), 0.5));
      if (!shape) continue;
      kinds.push_back(shape);
      mesh_draw_.push_back(std::make_unique<sc::demo::DrawMesh>(drawMeshOf(*shape)));
    }
    if (kinds.empty()) {
      std::fprintf(stderr,
                   options_.meshes.empty() ? "cannot read %s (run scripts/setup.sh)\n"
                                           : "no mesh could be loaded from --mesh %s ...\n",
                   paths.front().c_str());
      std::exit(1);
    }
    const std::vector<sc::demo::PileBodyPose> poses = sc::demo::pileBodyPoses(24, options_.seed);
    for (int i = 0; i < 24; ++i) {
      const std::size_t k = static_cast<std::size_t>(i) % kinds.size();
      const btVector3 p = poses[static_cast<std::size_t>(i)].position;
      Body b;
      b.body = addRigid(kinds[k].get(), 1.0, p);
      b.body->getWorldTransform().setRotation(poses[static_cast<std::size_t>(i)].rotation);
      b.mesh = mesh_draw_[mesh_draw_.size() - kinds.size() + k].get();
      b.start = p;
      const float palette[4][3] = {{0.85f, 0.45f, 0.25f}, {0.3f, 0.55f, 0.8f},
                                   {0.45f, 0.7f, 0.35f}, {0.8f, 0.7f, 0.3f}};
      std::memcpy(b.color, palette[i % 4], sizeof(b.color));
      bodies_.push_back(b);
    }
  }

  /// The first mesh is a static base (3 m), the others drop onto it (1 m each).
  void addMeshes() {
    std::vector<std::string> paths = options_.meshes;
    if (paths.empty())
      paths = {sc::demo::demoMesh("fandisk.off"), sc::demo::demoMesh("elephant.off"),
               sc::demo::demoMesh("elephant.off"), sc::demo::demoMesh("elephant.off")};
    double top = 0.0;
    for (std::size_t i = 0; i < paths.size(); ++i) {
      sc::MeshData mesh = sc::support::readOffOrEmpty(paths[i]);
      if (mesh.triangles.empty()) continue;
      const bool base = i == 0;
      auto shape = makeShape(sc::support::fitToSize(std::move(mesh), base ? 3.0 : 1.0));
      if (!shape) continue;
      mesh_draw_.push_back(std::make_unique<sc::demo::DrawMesh>(drawMeshOf(*shape)));
      btVector3 lo, hi;
      shape->getAabb(btTransform::getIdentity(), lo, hi);
      const double margin = shape->aabbMargin();
      Body b;
      if (base) {
        b.start = btVector3(0, btScalar(-(double(lo.y()) + margin)), 0);  // resting on the ground
        top = double(hi.y() - lo.y()) - 2 * margin;
      } else {
        const double x = 0.9 * (double(i) - 2.0);
        b.start = btVector3(btScalar(x), btScalar(top + 0.1 - double(lo.y()) + margin), btScalar(0.2 * double(i % 2)));
      }
      b.body = addRigid(shape.get(), base ? 0.0 : 1.0, b.start);
      b.mesh = mesh_draw_.back().get();
      b.color[0] = base ? 0.7f : 0.5f + 0.2f * float(i % 2);
      b.color[1] = base ? 0.7f : 0.55f;
      b.color[2] = base ? 0.6f : 0.75f - 0.2f * float(i % 2);
      if (base)
        base_ = b;
      else
        bodies_.push_back(b);
    }
    if (bodies_.empty()) {
      std::fprintf(stderr, "no mesh could be loaded; pass --mesh BASE.off --mesh BODY.off ...\n");
      std::exit(1);
    }
  }

  void clear() {
    if (bullet_.world)
      for (auto& b : rigid_) bullet_.world->removeRigidBody(b.get());
    rigid_.clear();
    bodies_.clear();
    walls_.clear();
    base_ = Body();
    bullet_.reset();
    mesh_draw_.clear();
    wall_draw_.clear();
    wall_shapes_.clear();
    shapes_.clear();
    rest_sum_ = 0.0;
    rest_samples_ = 0;
  }

  Options options_;
  sc::demo::BulletWorld<sc::bullet::ScDynamicsWorld> bullet_;
  std::unique_ptr<btBoxShape> ground_shape_;
  std::vector<std::shared_ptr<sc::bullet::ScBulletShape>> shapes_;
  std::shared_ptr<sc::bullet::ScBulletShape> box_;
  sc::demo::DrawMesh box_mesh_, ground_mesh_;
  std::vector<std::unique_ptr<sc::demo::DrawMesh>> mesh_draw_;
  std::vector<std::unique_ptr<btRigidBody>> rigid_;
  std::vector<Body> bodies_;  ///< the dynamic bodies (metrics)
  Body base_;                 ///< static mesh of the meshes scene
  std::vector<Body> walls_;   ///< static walls of the pile scene
  std::vector<std::unique_ptr<btBoxShape>> wall_shapes_;
  std::vector<std::unique_ptr<sc::demo::DrawMesh>> wall_draw_;
  long steps_ = 0;
  double step_seconds_ = 0.0, max_depth_ = 0.0, max_drift_ = 0.0;
  long non_finite_steps_ = 0, rss_after_1s_kb_ = 0;
  double start_energy_ = 0.0, max_energy_ = 0.0;
  double rest_sum_ = 0.0;
  int rest_samples_ = 0;
};

bool parse(int argc, char** argv, Options& o) {
  bool scene_set = false;
  for (int i = 1; i < argc; ++i) {
    if (sc::demo::readHeadlessOption(argc, argv, i, o)) continue;
    const std::string a = argv[i];
    std::string v;
    auto value = [&](std::string& out) { return sc::demo::nextValue(argc, argv, i, out); };
    if (a == "--scene" && value(v)) {
      o.scene = v;
      scene_set = true;
    } else if (a == "--model" && value(v)) {
      o.model = v == "manifold" ? ContactModel::Manifold : ContactModel::Potential;
    } else if (a == "--rotation" && value(v)) {
      o.rotation = v == "mix" ? sc::RotationMode::Mix : v == "free" ? sc::RotationMode::Free : sc::RotationMode::Input;
    } else if (a == "--hz" && value(v)) {
      o.hz = std::atof(v.c_str());
    } else if (a == "--seed" && value(v)) {
      o.seed = static_cast<unsigned>(std::strtoul(v.c_str(), nullptr, 10));
    } else if (a == "--steps" && value(v)) {
      o.steps = std::atol(v.c_str());
    } else if (a == "--mesh" && value(v)) {
      o.meshes.push_back(v);
    } else {
      std::fprintf(
          stderr,
          "usage: %s [--scene tower|pyramid|massratio|meshes|pile] [--model potential|manifold]\n"
          "          [--rotation input|mix|free] [--hz RATE (240)] [--seed N (pile, 7)]\n"
          "          [--mesh BASE.off --mesh BODY.off... (meshes) | --mesh BODY.off... (pile)]\n"
          "          [--headless [--seconds S | --steps N] [--png F] [--json F]]\n",
          argv[0]);
      return false;
    }
  }
  // Meshes alone ask for the meshes scene; with --scene pile they fill the pile.
  if (!o.meshes.empty() && !scene_set) o.scene = "meshes";
  return o.seconds > 0.0 && std::isfinite(o.seconds) && o.hz >= 1.0 && o.hz <= 1e5;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (!parse(argc, argv, options)) return 2;
  if (options.steps > 0) options.seconds = static_cast<double>(options.steps) / options.hz;
  Demo demo(options);
  sc::demo::ViewerCallbacks cb;
  cb.collect = [&](std::vector<sc::demo::DrawItem>& items) { demo.collect(items); };
  cb.overlay = [&] { return demo.overlay(); };
  if (options.headless) {
    const long steps = options.steps > 0 ? options.steps : std::lround(options.seconds * options.hz);
    for (long i = 0; i < steps; ++i) demo.step();
    const std::string metrics = demo.json();
    if (!sc::demo::emitMetrics(metrics, options.json)) return 1;
    if (!options.png.empty() &&
        !sc::demo::renderToPng(argc, argv, cb, demo.targetY(), demo.distance(), options.png))
      return 1;
    return 0;
  }
  cb.step = [&] {
    // The physics rate at about 60 frames per second (4 steps a frame at 240 Hz).
    const long per_frame = std::max(1L, std::lround(options.hz / 60.0));
    for (long i = 0; i < per_frame; ++i) demo.step();
  };
  cb.key = [&](unsigned char k) {
    if (k == 'm') demo.toggleModel();
    if (k == 'r') demo.build();
    if (k == '1') demo.setScene("tower");
    if (k == '2') demo.setScene("pyramid");
    if (k == '3') demo.setScene("massratio");
    if (k == '4') demo.setScene("meshes");
    if (k == '5') demo.setScene("pile");
  };
  sc::demo::runViewer(argc, argv, "SmartCollision stacking", cb, demo.targetY(), demo.distance());
  return 0;
}
