// SPDX-License-Identifier: MIT
// Haptic coupling demo (manual 9-10.3 on Bullet): a 6-DOF device drives one rigid
// body through a virtual spring-damper. Three loops:
//   haptic thread   1 kHz: poll the device, compute the coupling reaction from the
//                   latest body state, hand it to the device;
//   physics thread  1 kHz, 500 Hz for the cavity (--physics-hz): apply the coupling to the body
//   with the
//                   latest device pose, step Bullet + SmartCollision;
//   graphics        the GLUT loop in the main thread (not run with --headless).
// Poses and body states pass through seqlocks (lock-free for the reader and the
// single writer). Scenes: `peg` (square peg into a block with a square through-hole,
// 2 mm clearance per side) and `cavity` (the bunny, 75k triangles, into a cup).
// With --loop a recorded script plays back and forth until --seconds: the soak of
// bench/soak_haptic.sh, whose NaN, energy and memory figures the JSON reports.
#include <btBulletDynamicsCommon.h>
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "../common/cli.h"
#include "../common/device.h"
#include "../common/off_mesh.h"
#include "../common/viewer.h"
#include "smartcollision/bullet/bullet.h"

namespace {

using Clock = std::chrono::steady_clock;
using sc::Quat;
using sc::Vec3;

constexpr double kHapticHz = 1000.0;
constexpr double kMaxDeviceSpeed = 0.1;  ///< [m/s] the scripted runs stay below (force-jump bound)
/// Haptic samples after a missed deadline (either loop) that the force-jump bound does
/// not cover: the coupling's time constant (1 / omega, about 3 ms) several times over.
constexpr int kSettleSamples = 20;

/// Single writer, any number of readers; N doubles, every word atomic (no data race).
template <std::size_t N>
class SeqLock {
 public:
  void write(const std::array<double, N>& v) {
    const unsigned s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_release);
    for (std::size_t i = 0; i < N; ++i) data_[i].store(v[i], std::memory_order_relaxed);
    seq_.store(s + 2, std::memory_order_release);
  }
  /// False until the first write, and when the writer was mid-write for every one of
  /// a few attempts (preempted there: a reader that spun would wait for it, and a
  /// FIFO haptic thread could wait on its own core); `out` is then left as it was.
  bool read(std::array<double, N>& out) const {
    std::array<double, N> copy;
    for (int attempt = 0; attempt < 64; ++attempt) {
      const unsigned s0 = seq_.load(std::memory_order_acquire);
      if (s0 == 0) return false;
      if (s0 & 1u) continue;
      for (std::size_t i = 0; i < N; ++i) copy[i] = data_[i].load(std::memory_order_relaxed);
      std::atomic_thread_fence(std::memory_order_acquire);
      if (seq_.load(std::memory_order_relaxed) == s0) {
        out = copy;
        return true;
      }
    }
    return false;
  }

 private:
  std::atomic<unsigned> seq_{0};
  std::array<std::atomic<double>, N> data_{};
};

using PoseWords = std::array<double, 7>;    // x y z qw qx qy qz
using StateWords = std::array<double, 15>;  // pose, v, w, physics step count, in contact

PoseWords wordsOf(const sc::bullet::CouplingPose& p) {
  return {p.position.x(),    p.position.y(),    p.position.z(),   p.orientation.w(),
          p.orientation.x(), p.orientation.y(), p.orientation.z()};
}
sc::bullet::CouplingPose poseOf(const double* w) {
  sc::bullet::CouplingPose p;
  p.position = Vec3(w[0], w[1], w[2]);
  p.orientation = Quat(w[3], w[4], w[5], w[6]).normalized();
  return p;
}
StateWords wordsOf(const sc::bullet::BodyState& s) {
  StateWords w{};
  const PoseWords p = wordsOf(s.pose);
  std::copy(p.begin(), p.end(), w.begin());
  for (int k = 0; k < 3; ++k) {
    w[std::size_t(7 + k)] = s.linear_velocity[k];
    w[std::size_t(10 + k)] = s.angular_velocity[k];
  }
  return w;
}
sc::bullet::BodyState stateOf(const StateWords& w) {
  sc::bullet::BodyState s;
  s.pose = poseOf(w.data());
  s.linear_velocity = Vec3(w[7], w[8], w[9]);
  s.angular_velocity = Vec3(w[10], w[11], w[12]);
  return s;
}

/// seconds 0: the script's length + 1 s (headless), unlimited otherwise.
struct Options : sc::demo::HeadlessOptions {
  std::string scene = "peg";
  std::string device = "mouse";
  double physics_hz = 0.0;  ///< 0: 1000 Hz for peg, 500 Hz for cavity (75k triangles)
  std::string wrench_log;   ///< script device: the rendered wrenches, one line per sample
  bool loop = false;        ///< script device: play back and forth (a soak with --seconds)
  bool lockstep = false;    ///< headless: haptic and physics in turn on simulated time
};

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

/// Scales a mesh so that its largest AABB extent is `size`, centred on its box.
sc::MeshData normalised(sc::MeshData m, double size) {
  sc::Aabb box;
  for (const Vec3& v : m.vertices) box.extend(v);
  const double extent = (box.max - box.min).maxCoeff();
  const Vec3 c = 0.5 * (box.min + box.max);
  for (Vec3& v : m.vertices) v = (v - c) * (size / (extent > 0 ? extent : 1.0));
  return m;
}

sc::demo::DrawMesh drawMeshOf(const sc::bullet::ScBulletShape& shape) {
  sc::demo::DrawMesh m;
  for (const btVector3& v : shape.vertices())
    m.vertices.insert(m.vertices.end(), {float(v.x()), float(v.y()), float(v.z())});
  m.indices = shape.indices();
  return m;
}

/// Haptic periods in 1 us bins up to 50 ms (longer ones in the last bin), plus the
/// exact maximum: fixed memory, so that a soak's resident size does not grow with it.
class PeriodHistogram {
 public:
  void add(double seconds) {
    const double us = std::max(0.0, seconds * 1e6);
    ++bins_[std::min(bins_.size() - 1, std::size_t(us))];
    ++count_;
    max_ = std::max(max_, seconds);
  }
  long count() const { return count_; }
  double max() const { return max_; }
  /// The p-quantile [s], to the bin's centre (0.5 us).
  double percentile(double p) const {
    if (count_ == 0) return 0.0;
    const long rank = std::min(count_ - 1, long(p * double(count_ - 1) + 0.5));
    long seen = 0;
    for (std::size_t i = 0; i < bins_.size(); ++i) {
      seen += bins_[i];
      if (seen > rank) return std::min(max_, (double(i) + 0.5) * 1e-6);
    }
    return max_;
  }

 private:
  std::vector<long> bins_ = std::vector<long>(50000, 0);
  long count_ = 0;
  double max_ = 0.0;
};

/// Resident set size now [kB] (/proc/self/statm), 0 when unavailable.
long residentKb() {
  long pages = 0, resident = 0;
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return 0;
  if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
  std::fclose(f);
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

long peakResidentKb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

bool finite(const sc::bullet::BodyState& s) {
  return s.pose.position.allFinite() && s.pose.orientation.coeffs().allFinite() &&
         s.linear_velocity.allFinite() && s.angular_velocity.allFinite();
}

bool finite(const sc::bullet::CouplingWrench& w) {
  return w.force.allFinite() && w.torque.allFinite();
}

/// Kinetic energy of a body [J] (translation + rotation about its principal axes).
double kineticEnergy(const btRigidBody& b) {
  const btVector3 v = b.getLinearVelocity();
  const btVector3 w = b.getWorldTransform().getBasis().transpose() * b.getAngularVelocity();
  const btVector3 inv_i = b.getInvInertiaDiagLocal();
  double e = b.getInvMass() > 0 ? 0.5 * double(v.length2()) / double(b.getInvMass()) : 0.0;
  for (int k = 0; k < 3; ++k)
    if (inv_i[k] > 0) e += 0.5 * double(w[k]) * double(w[k]) / double(inv_i[k]);
  return e;
}

class Demo {
 public:
  explicit Demo(const Options& o, std::unique_ptr<sc::demo::Device> device)
      : options_(o), device_(std::move(device)), physics_dt_(1.0 / o.physics_hz) {
    config_ =
        std::make_unique<btDefaultCollisionConfiguration>(sc::bullet::collisionConstructionInfo());
    dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
    auto plugin = sc::bullet::registerSmartCollision(dispatcher_.get(), {});
    if (!plugin.ok()) fail("registerSmartCollision: " + plugin.status().message());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
    world_ = std::make_unique<sc::bullet::ScDynamicsWorld>(
        dispatcher_.get(), broadphase_.get(), solver_.get(), config_.get(), plugin.value());
    world_->setGravity(btVector3(0, -9.81f, 0));
    if (o.scene == "cavity")
      buildCavity();
    else
      buildPeg();
    design_.physics_dt = physics_dt_;
    design_.haptic_dt = 1.0 / kHapticHz;
    coupling_ = std::make_unique<sc::bullet::VirtualCoupling>(
        sc::bullet::designCouplingGains(*tool_, design_));
    passivity_ = sc::bullet::checkPassivity(coupling_->gains(), design_);
    sc::demo::DevicePose home;
    for (int k = 0; k < 3; ++k) home.position[k] = tool_home_[k];
    device_->setHome(home);
    sc::bullet::CouplingPose home_pose;
    home_pose.position = tool_home_;
    device_pose_.write(wordsOf(home_pose));
    body_state_.write(wordsOf(sc::bullet::bodyStateOf(*tool_)));
    device_pose_.read(physics_device_);
    body_state_.read(haptic_body_);
  }

  ~Demo() {
    stop();
    for (auto& b : rigid_) world_->removeRigidBody(b.get());
  }

  void start() {
    start_time_ = rate_time_ = Clock::now();
    running_ = true;
    physics_ = std::thread([this] { physicsLoop(); });
    haptic_ = std::thread([this] { hapticLoop(); });
  }

  /// --lockstep: the haptic samples and physics steps of `seconds` of simulated time in
  /// this thread, on a simulated clock (`clock`, which drives the script device), so
  /// the outcome does not depend on how loaded the machine is. The threaded run is
  /// what the rates and periods of docs/benchmarks.md measure.
  void runLockstep(double seconds, std::atomic<double>& clock) {
    lockstep_ = true;
    const auto wall = Clock::now();
    const long samples = std::lround(seconds * kHapticHz);
    for (long k = 0; k < samples; ++k) {
      clock = double(k) / kHapticHz;
      hapticSample(k == 0 ? 0.0 : 1.0 / kHapticHz);
      const double until = double(k + 1) / kHapticHz;  // physics catches up to the next sample
      while (double(physics_count_.load() + 1) * physics_dt_ <= until + 1e-9) physicsStep();
    }
    elapsed_ = double(samples) / kHapticHz;
    wall_seconds_ = std::chrono::duration<double>(Clock::now() - wall).count();
  }

  void stop() {
    running_ = false;
    if (haptic_.joinable()) haptic_.join();
    if (physics_.joinable()) physics_.join();
    elapsed_ = std::chrono::duration<double>(Clock::now() - start_time_).count();
    wall_seconds_ = elapsed_;
  }

  sc::demo::Device& device() { return *device_; }
  double defaultSeconds() const { return scriptLength() > 0 ? scriptLength() + 1.0 : 10.0; }

  void collect(std::vector<sc::demo::DrawItem>& items) {
    ++frames_;
    auto push = [&](const sc::demo::DrawMesh* mesh, const btTransform& t, const float* color,
                    float scale) {
      sc::demo::DrawItem item;
      item.mesh = mesh;
      btScalar m[16];
      t.getOpenGLMatrix(m);
      for (int i = 0; i < 16; ++i)
        item.matrix[i] = float(m[i]) * (i < 12 && i % 4 < 3 ? scale : 1.0f);
      std::memcpy(item.color, color, sizeof(item.color));
      items.push_back(item);
    };
    const float ground_color[3] = {0.55f, 0.6f, 0.65f};
    btTransform ground(btQuaternion::getIdentity(), btVector3(0, -0.01f, 0));
    sc::demo::DrawItem g;
    g.mesh = &cube_mesh_;
    btScalar gm[16];
    ground.getOpenGLMatrix(gm);
    for (int i = 0; i < 16; ++i) g.matrix[i] = float(gm[i]);
    g.matrix[0] = 0.3f;  // unit cube stretched to a 0.6 x 0.02 x 0.6 m slab
    g.matrix[5] = 0.01f;
    g.matrix[10] = 0.3f;
    std::memcpy(g.color, ground_color, sizeof(g.color));
    items.push_back(g);
    push(&fixed_mesh_, fixed_->getWorldTransform(), fixed_color_, 1.0f);
    StateWords w{};
    body_state_.read(w);
    const sc::bullet::BodyState s = stateOf(w);
    const btTransform body(
        btQuaternion(btScalar(s.pose.orientation.x()), btScalar(s.pose.orientation.y()),
                     btScalar(s.pose.orientation.z()), btScalar(s.pose.orientation.w())),
        btVector3(btScalar(s.pose.position.x()), btScalar(s.pose.position.y()),
                  btScalar(s.pose.position.z())));
    push(&tool_mesh_, body, tool_color_, 1.0f);
    PoseWords d{};
    device_pose_.read(d);
    const float ghost[3] = {0.2f, 0.75f, 0.3f};
    push(&cube_mesh_,
         btTransform(btQuaternion(btScalar(d[4]), btScalar(d[5]), btScalar(d[6]), btScalar(d[3])),
                     btVector3(btScalar(d[0]), btScalar(d[1]), btScalar(d[2]))),
         ghost, 0.006f);
  }

  std::string overlay() {
    const auto now = Clock::now();
    const double dt = std::chrono::duration<double>(now - rate_time_).count();
    if (!running_ && elapsed_ > 0.0) {  // a finished headless run: its mean rates
      haptic_rate_ = double(haptic_count_.load()) / elapsed_;
      physics_rate_ = double(physics_count_.load()) / elapsed_;
      frame_rate_ = 0.0;
    } else if (dt >= 0.5) {
      const long h = haptic_count_.load(), p = physics_count_.load(), f = frames_;
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
    const std::string graphics =
        !running_ && elapsed_ > 0.0 ? std::string("(headless run)") : std::string(fps);
    char buf[768];
    std::snprintf(
        buf, sizeof(buf),
        "scene %s   device %s\n"
        "haptic %.0f Hz   physics %.0f Hz   graphics %s\n"
        "coupling force %.1f N (max %.0f N)   max depth %.2f mm   energy generated %.2e J\n%s",
        options_.scene.c_str(), device_->name(), haptic_rate_, physics_rate_, graphics.c_str(),
        last_force_.load(), coupling_->gains().max_force, 1e3 * max_depth_.load(),
        generated_.load(), device_->status().c_str());
    return buf;
  }

  std::string json() const {
    const sc::bullet::CouplingGains& g = coupling_->gains();
    const sc::bullet::BodyState s = sc::bullet::bodyStateOf(*tool_);
    // Nominal bound: one haptic period of device motion, one physics step of the body.
    const double jump_bound =
        sc::bullet::forceJumpBound(g, kMaxDeviceSpeed, 1.0 / kHapticHz, physics_dt_);
    const double impact_bound =
        sc::bullet::impactJumpBound(g, kMaxDeviceSpeed, 1.0 / kHapticHz, physics_dt_);
    const Vec3 r =
        sc::bullet::rotationVector(s.pose.orientation * grip_rotation_.conjugate());  // mesh frame
    char buf[4096];
    std::snprintf(
        buf, sizeof(buf),
        "{\n  \"scene\": \"%s\",\n  \"device\": \"%s\",\n  \"clock\": \"%s\",\n  \"haptic_fifo\": "
        "%s,\n  "
        "\"wall_seconds\": %.3f,\n  \"tool_triangles\": %zu,\n  "
        "\"fixed_triangles\": %zu,\n"
        "  \"seconds\": %.3f,\n  \"haptic_samples\": %ld,\n  \"haptic_rate_hz\": %.1f,\n"
        "  \"haptic_period_p50_ms\": %.4f,\n  \"haptic_period_p99_ms\": %.4f,\n  "
        "\"haptic_period_max_ms\": %.4f,\n"
        "  \"physics_steps\": %ld,\n  \"physics_rate_hz\": %.1f,\n  \"physics_ms_per_step\": "
        "%.4f,\n  \"physics_step_max_ms\": %.3f,\n  \"physics_steps_over_period\": %ld,\n"
        "  \"gains\": {\"k_t\": %.1f, \"b_t\": %.2f, \"k_r\": %.4f, \"b_r\": %.5f, \"max_force\": "
        "%.2f, "
        "\"max_torque\": %.4f},\n"
        "  \"passivity_body_margin\": %.2f,\n  \"required_device_damping\": %.3f,\n"
        "  \"max_force_jump_N\": %.4f,\n  \"force_jump_bound_N\": %.4f,\n  "
        "\"max_force_jump_ratio\": %.4f,\n  \"impacts\": %ld,\n  \"max_impact_jump_N\": %.4f,\n  "
        "\"impact_jump_bound_N\": %.4f,\n  \"max_impact_jump_ratio\": %.4f,\n  "
        "\"max_force_jump_any_N\": %.4f,\n  "
        "\"samples_after_missed_deadline\": %ld,\n  "
        "\"max_coupling_force_N\": %.4f,\n"
        "  \"energy_generated_J\": %.6g,\n  \"energy_generated_max_J\": %.6g,\n  "
        "\"coupling_work_on_body_J\": %.6g,\n"
        "  \"device_work_J\": %.6g,\n  \"spring_energy_J\": %.6g,\n  \"kinetic_energy_change_J\": "
        "%.6g,\n"
        "  \"max_kinetic_energy_J\": %.6g,\n  \"non_finite_steps\": %ld,\n  "
        "\"non_finite_samples\": %ld,\n"
        "  \"rss_after_1s_kB\": %ld,\n  \"rss_after_60s_kB\": %ld,\n  \"rss_end_kB\": %ld,\n  "
        "\"peak_rss_kB\": %ld,\n"
        "  \"max_penetration_m\": %.6f,\n  \"final_position\": [%.5f, %.5f, %.5f],\n"
        "  \"final_rotation_vector\": [%.5f, %.5f, %.5f],\n  \"inserted_depth_m\": %.5f,\n  "
        "\"inside\": %s\n}\n",
        options_.scene.c_str(), device_->name(), lockstep_ ? "lockstep" : "realtime",
        haptic_fifo_.load() ? "true" : "false", wall_seconds_, tool_triangles_, fixed_triangles_,
        elapsed_, periods_.count() + 1,
        elapsed_ > 0 ? double(haptic_count_.load()) / elapsed_ : 0.0,
        1e3 * periods_.percentile(0.5), 1e3 * periods_.percentile(0.99), 1e3 * periods_.max(),
        physics_count_.load(), elapsed_ > 0 ? double(physics_count_.load()) / elapsed_ : 0.0,
        physics_count_.load() ? 1e3 * step_seconds_ / double(physics_count_.load()) : 0.0,
        1e3 * step_max_, steps_over_period_, g.linear_stiffness, g.linear_damping,
        g.angular_stiffness, g.angular_damping, g.max_force, g.max_torque, passivity_.body_margin,
        passivity_.required_device_damping, max_jump_, jump_bound, max_jump_ratio_, impacts_,
        max_impact_jump_, impact_bound, max_impact_ratio_, max_jump_any_, unchecked_samples_,
        max_coupling_force_, monitor_.generated(), monitor_.maxGenerated(), monitor_.bodyWork(),
        monitor_.deviceWork(), monitor_.springEnergy(), monitor_.kineticEnergyChange(),
        max_kinetic_, non_finite_steps_, non_finite_samples_, rss_after_1s_kb_, rss_after_60s_kb_,
        residentKb(), std::max(peakResidentKb(), residentKb()), max_depth_.load(),
        s.pose.position.x(), s.pose.position.y(), s.pose.position.z(), r.x(), r.y(), r.z(),
        insertedDepth(s), inside(s) ? "true" : "false");
    return buf;
  }

  float targetY() const { return 0.07f; }
  float distance() const { return 0.55f; }

 private:
  [[noreturn]] static void fail(const std::string& what) {
    std::fprintf(stderr, "%s\n", what.c_str());
    std::exit(1);
  }

  std::shared_ptr<sc::bullet::ScBulletShape> makeShape(const sc::MeshData& mesh,
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
  btRigidBody* addRigid(const sc::bullet::ScBulletShape& shape, double mass,
                        const btTransform& world_from_mesh) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape.calculateLocalInertia(btScalar(mass), inertia);
    btRigidBody::btRigidBodyConstructionInfo ci(
        btScalar(mass), nullptr, const_cast<sc::bullet::ScBulletShape*>(&shape), inertia);
    ci.m_startWorldTransform = world_from_mesh * shape.meshFromShape();
    rigid_.push_back(std::make_unique<btRigidBody>(ci));
    btRigidBody* b = rigid_.back().get();
    b->setActivationState(DISABLE_DEACTIVATION);
    world_->addRigidBody(b);
    return b;
  }

  /// The held tool: no gravity (the device carries it), coupled to the device.
  void setTool(btRigidBody* body, const sc::bullet::ScBulletShape& shape) {
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
    sc::bullet::ContactSettings soft = world_->plugin().settings().contact;
    const double omega = 2.0 * 3.141592653589793 / (soft.contact_period_steps * physics_dt_);
    soft.force_stiffness = double(1.0 / tool_->getInvMass()) * omega * omega;
    if (!world_->plugin().setBodySettings(tool_, soft).ok()) fail("setBodySettings");
  }

  void buildCommon() {
    auto cube = makeShape(boxMesh(Vec3(1, 1, 1)), sc::ModelKind::ClosedPolyhedron);
    cube_mesh_ = drawMeshOf(*cube);
  }

  // Peg scene: block 200 x 80 x 200 mm with a 50 mm square through-hole, top at
  // y = 80 mm; peg 46 x 120 x 46 mm, 0.5 kg.
  void buildPeg() {
    buildCommon();
    hole_half_ = 0.025;
    block_top_ = 0.08;
    auto block =
        makeShape(holedBlock(0.1, hole_half_, block_top_, 0.0), sc::ModelKind::ClosedPolyhedron);
    if (!block) fail("holed block: not a valid closed polyhedron");
    fixed_ = addRigid(*block, 0.0, btTransform::getIdentity());
    fixed_mesh_ = drawMeshOf(*block);
    fixed_triangles_ = block->indices().size() / 3;
    tool_half_ = Vec3(0.023, 0.06, 0.023);
    auto peg = makeShape(boxMesh(tool_half_), sc::ModelKind::ClosedPolyhedron);
    tool_home_ = Vec3(0, 0.17, 0);
    setTool(addRigid(*peg, 0.5, btTransform(btQuaternion::getIdentity(), btVector3(0, 0.17f, 0))),
            *peg);
    tool_mesh_ = drawMeshOf(*peg);
    tool_triangles_ = peg->indices().size() / 3;
  }

  // Cavity scene: a cup 200 x 120 x 200 mm with a 140 mm square pocket 80 mm deep;
  // the bunny (bunny00.off, 75k triangles) scaled to 100 mm, 0.5 kg.
  void buildCavity() {
    buildCommon();
    hole_half_ = 0.07;
    block_top_ = 0.12;
    auto cup =
        makeShape(holedBlock(0.1, hole_half_, block_top_, 0.04), sc::ModelKind::ClosedPolyhedron);
    if (!cup) fail("cup: not a valid closed polyhedron");
    fixed_ = addRigid(*cup, 0.0, btTransform::getIdentity());
    fixed_mesh_ = drawMeshOf(*cup);
    fixed_triangles_ = cup->indices().size() / 3;
    const std::string bunny_file = sc::demo::demoMesh("bunny00.off");
    sc::MeshData bunny = sc::demo::readOff(bunny_file);
    if (bunny.triangles.empty()) fail("cannot read " + bunny_file + " (run scripts/setup.sh)");
    bunny = normalised(std::move(bunny), 0.1);
    auto tool = makeShape(bunny, sc::ModelKind::ClosedPolyhedron);
    if (!tool) tool = makeShape(bunny, sc::ModelKind::TriangleSoup);
    if (!tool) fail("bunny: cannot build the model");
    btVector3 lo, hi;
    tool->getAabb(btTransform::getIdentity(), lo, hi);
    tool_half_ = Vec3(0.5 * double(hi.x() - lo.x()), 0.5 * double(hi.y() - lo.y()),
                      0.5 * double(hi.z() - lo.z())) -
                 Vec3::Constant(tool->aabbMargin());
    tool_home_ = Vec3(0, 0.2, 0);
    setTool(addRigid(*tool, 0.5, btTransform(btQuaternion::getIdentity(), btVector3(0, 0.2f, 0))),
            *tool);
    tool_mesh_ = drawMeshOf(*tool);
    tool_triangles_ = tool->indices().size() / 3;
    tool_color_[0] = 0.85f;
    tool_color_[1] = 0.7f;
    tool_color_[2] = 0.45f;
  }

  /// The device holds the tool's mesh frame; the coupling pulls the body (shape frame).
  sc::bullet::CouplingPose bodyTarget(const sc::bullet::CouplingPose& device) const {
    sc::bullet::CouplingPose t;
    t.position = device.position + device.orientation * grip_position_;
    t.orientation = (device.orientation * grip_rotation_).normalized();
    return t;
  }

  double scriptLength() const {
    const std::string prefix = "script:";
    if (options_.device.compare(0, prefix.size(), prefix) != 0) return 0.0;
    auto s = sc::bullet::PoseScript::load(options_.device.substr(prefix.size()));
    return s.ok() ? s.value().duration() : 0.0;
  }

  /// How far the tool's lowest point is below the top of the block [m].
  double insertedDepth(const sc::bullet::BodyState& s) const {
    return block_top_ - (s.pose.position.y() - tool_half_.y());
  }
  /// Peg: centre within the hole's clearance (+1 mm), at least 20 mm below the top.
  /// Cavity: the tool's box within the pocket's walls and below its rim.
  bool inside(const sc::bullet::BodyState& s) const {
    const double lateral = std::max(std::abs(s.pose.position.x()), std::abs(s.pose.position.z()));
    if (options_.scene == "cavity")
      return lateral + std::max(tool_half_.x(), tool_half_.z()) <= hole_half_ + 0.002 &&
             s.pose.position.y() + tool_half_.y() <= block_top_ + 0.02 && insertedDepth(s) > 0.04;
    return lateral <= hole_half_ - tool_half_.x() + 0.001 && insertedDepth(s) >= 0.02;
  }

  void physicsLoop() {
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
  void physicsStep() {
    device_pose_.read(physics_device_);  // kept as it was if the writer is mid-write
    const sc::bullet::CouplingPose device = bodyTarget(poseOf(physics_device_.data()));
    const auto t0 = Clock::now();
    const sc::bullet::CouplingWrench w = coupling_->apply(device, *tool_);
    monitor_.beforeStep(*coupling_, device, *tool_, w);
    world_->stepSimulation(btScalar(physics_dt_), 1, btScalar(physics_dt_));
    monitor_.afterStep(*tool_);
    const double step = std::chrono::duration<double>(Clock::now() - t0).count();
    step_seconds_ += step;
    step_max_ = std::max(step_max_, step);
    if (step > physics_dt_) ++steps_over_period_;
    max_depth_ = std::max(max_depth_.load(), world_->plugin().stats().max_depth);
    generated_ = monitor_.generated();
    const sc::bullet::BodyState body = sc::bullet::bodyStateOf(*tool_);
    recordHealth(body, w);
    StateWords state = wordsOf(body);
    state[13] = double(physics_count_.load() + 1);
    state[14] = world_->plugin().stats().touching > 0 ? 1.0 : 0.0;
    body_state_.write(state);
    ++physics_count_;
  }

  /// Physics thread, after each step: what a soak watches (NaN, energy, memory).
  void recordHealth(const sc::bullet::BodyState& body, const sc::bullet::CouplingWrench& w) {
    if (!finite(body) || !finite(w)) ++non_finite_steps_;
    max_kinetic_ = std::max(max_kinetic_, kineticEnergy(*tool_));
    const long step = physics_count_.load() + 1;
    const long per_second = std::lround(options_.physics_hz);
    if (step == per_second) rss_after_1s_kb_ = residentKb();
    if (step == 60 * per_second) rss_after_60s_kb_ = residentKb();
  }

  void hapticLoop() {
    haptic_fifo_ = raiseToRealTime();
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

  /// A haptic loop's deadline is a millisecond: ask for FIFO scheduling above every
  /// ordinary thread (the physics thread included), as haptic applications do. It
  /// needs CAP_SYS_NICE or an rtprio limit; without them the loop runs as before.
  /// Safe because the loop sleeps between samples (microseconds of work per period).
  static bool raiseToRealTime() {
    sched_param param{};
    param.sched_priority = sched_get_priority_min(SCHED_FIFO) + 10;
    return pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0;
  }

  /// One haptic sample, `interval` seconds after the previous one (0 for the first):
  /// poll the device, the reaction from the latest body state to the device, and the
  /// force-continuity check.
  void hapticSample(double interval) {
    const bool first = haptic_count_.load() == 0;
    if (!first) periods_.add(interval);
    sc::demo::DevicePose p;
    if (device_->poll(p)) {
      sc::bullet::CouplingPose pose;
      pose.position = Vec3(p.position[0], p.position[1], p.position[2]);
      pose.orientation =
          Quat(p.orientation[0], p.orientation[1], p.orientation[2], p.orientation[3]).normalized();
      device_pose_.write(wordsOf(pose));
      body_state_.read(haptic_body_);  // kept as it was if the writer is mid-write
      const StateWords& s = haptic_body_;
      const sc::bullet::CouplingWrench r = coupling_->reaction(bodyTarget(pose), stateOf(s));
      if (!finite(stateOf(s)) || !finite(r)) ++non_finite_samples_;
      sc::demo::Wrench out;
      for (int k = 0; k < 3; ++k) {
        out.force[k] = r.force[k];
        out.torque[k] = r.torque[k];
      }
      device_->render(out);
      const bool contact = s[14] > 0.5;
      if (contact && !previous_contact_) {
        since_impact_ = 0;
        ++impacts_;
      }
      previous_contact_ = contact;
      if (!first) checkForceJump(r.force, interval, (s[13] - previous_steps_) * physics_dt_);
      previous_steps_ = s[13];
      max_coupling_force_ = std::max(max_coupling_force_, r.force.norm());
      last_force_ = r.force.norm();
      previous_force_ = r.force;
    }
    ++haptic_count_;
  }

  /// The bound for this pair of samples: the device moved for `interval`, the body for
  /// `body_interval` (the physics steps taken in between); within kSettleSamples of a
  /// contact's onset the impact bound (the body stops at once). It assumes both loops
  /// keep their rates: after a missed deadline the body catches up faster than the
  /// bound's speed, so pairs within kSettleSamples of one are only counted.
  void checkForceJump(const Vec3& force, double interval, double body_interval) {
    if (interval > 1.5 / kHapticHz || body_interval > 2.5 * physics_dt_) since_miss_ = 0;
    const double jump = (force - previous_force_).norm();
    max_jump_any_ = std::max(max_jump_any_, jump);
    const bool impact = since_impact_ < kSettleSamples;
    if (impact) ++since_impact_;
    if (since_miss_ < kSettleSamples) {
      ++since_miss_;
      ++unchecked_samples_;
      return;
    }
    const sc::bullet::CouplingGains& g = coupling_->gains();
    if (impact) {
      const double bound = sc::bullet::impactJumpBound(g, kMaxDeviceSpeed, interval, body_interval);
      max_impact_jump_ = std::max(max_impact_jump_, jump);
      max_impact_ratio_ = std::max(max_impact_ratio_, jump / bound);
      return;
    }
    const double bound = sc::bullet::forceJumpBound(g, kMaxDeviceSpeed, interval, body_interval);
    max_jump_ = std::max(max_jump_, jump);
    max_jump_ratio_ = std::max(max_jump_ratio_, jump / bound);
  }

  Options options_;
  std::unique_ptr<sc::demo::Device> device_;
  double physics_dt_;
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<sc::bullet::ScDynamicsWorld> world_;
  std::vector<std::shared_ptr<sc::bullet::ScBulletShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> rigid_;
  btRigidBody* tool_ = nullptr;
  btRigidBody* fixed_ = nullptr;
  sc::demo::DrawMesh tool_mesh_, fixed_mesh_, cube_mesh_;
  float tool_color_[3] = {0.85f, 0.45f, 0.25f};
  float fixed_color_[3] = {0.45f, 0.55f, 0.75f};
  std::size_t tool_triangles_ = 0, fixed_triangles_ = 0;
  Vec3 tool_half_ = Vec3::Zero();
  Vec3 tool_home_ = Vec3::Zero();      ///< the tool's mesh frame at the start
  Vec3 grip_position_ = Vec3::Zero();  ///< the tool's shape frame in its mesh frame
  Quat grip_rotation_ = Quat::Identity();
  double hole_half_ = 0.0, block_top_ = 0.0;

  sc::bullet::CouplingDesign design_;
  std::unique_ptr<sc::bullet::VirtualCoupling> coupling_;
  sc::bullet::PassivityReport passivity_;
  sc::bullet::CouplingEnergyMonitor monitor_;  ///< physics thread

  SeqLock<7> device_pose_;  ///< haptic -> physics, graphics
  SeqLock<15> body_state_;
  PoseWords physics_device_{};  ///< physics thread: the last device pose read
  StateWords haptic_body_{};  ///< haptic thread: the last body state read  ///< physics -> haptic,
                              ///< graphics
  std::atomic<bool> running_{false};
  std::thread physics_, haptic_;
  Clock::time_point start_time_;
  double elapsed_ = 0.0;       ///< seconds of the run: simulated with --lockstep
  double wall_seconds_ = 0.0;  ///< wall time of the run
  bool lockstep_ = false;
  std::atomic<bool> haptic_fifo_{false};  ///< the haptic thread got FIFO scheduling

  // Metrics (each written by one thread, read after the join or as a display value).
  std::atomic<long> haptic_count_{0}, physics_count_{0};
  PeriodHistogram periods_;
  int since_miss_ = 1 << 30;            ///< haptic samples since a loop missed its deadline
  Vec3 previous_force_ = Vec3::Zero();  ///< haptic thread: the last sample's reaction
  double previous_steps_ = 0.0;         ///< haptic thread: physics steps at the last sample
  bool previous_contact_ = false;       ///< haptic thread: the tool touched at the last sample
  int since_impact_ = 1 << 30;          ///< haptic samples since a contact's onset
  long impacts_ = 0;                    ///< contact onsets seen by the haptic loop
  double max_impact_jump_ = 0.0, max_impact_ratio_ = 0.0;
  long unchecked_samples_ = 0;
  double max_jump_any_ = 0.0;
  long non_finite_samples_ = 0;  ///< haptic samples with a non-finite body state or reaction
  long non_finite_steps_ = 0;    ///< physics steps with a non-finite body state or wrench
  long steps_over_period_ = 0;   ///< physics steps that took longer than their period
  double max_kinetic_ = 0.0;     ///< the tool's largest kinetic energy [J]
  long rss_after_1s_kb_ = 0, rss_after_60s_kb_ = 0;  ///< 0 when the run is shorter
  double max_jump_ = 0.0, max_jump_ratio_ = 0.0, max_coupling_force_ = 0.0, step_seconds_ = 0.0,
         step_max_ = 0.0;
  std::atomic<double> max_depth_{0.0}, generated_{0.0}, last_force_{0.0};
  // Overlay rates (graphics thread).
  long frames_ = 0, rate_haptic_ = 0, rate_physics_ = 0, rate_frames_ = 0;
  double haptic_rate_ = 0.0, physics_rate_ = 0.0, frame_rate_ = 0.0;
  Clock::time_point rate_time_ = Clock::now();
};

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    if (sc::demo::readHeadlessOption(argc, argv, i, o)) continue;
    const std::string a = argv[i];
    std::string v;
    auto value = [&](std::string& out) { return sc::demo::nextValue(argc, argv, i, out); };
    if (a == "--scene" && value(v) && (v == "peg" || v == "cavity")) {
      o.scene = v;
    } else if (a == "--device" && value(v)) {
      const std::string script = "script:";  // an installed script is found by its name
      o.device =
          v.rfind(script, 0) == 0 ? script + sc::demo::demoScript(v.substr(script.size())) : v;
    } else if (a == "--physics-hz" && value(v)) {
      o.physics_hz = std::atof(v.c_str());
    } else if (a == "--wrench-log" && value(v)) {
      o.wrench_log = v;
    } else if (a == "--loop") {
      o.loop = true;
    } else if (a == "--lockstep") {
      o.lockstep = true;
    } else {
      std::fprintf(stderr,
                   "usage: %s [--scene peg|cavity] [--device mouse|spacemouse|script:FILE]\n"
                   "          [--physics-hz HZ] [--loop] [--headless [--lockstep] [--seconds S] "
                   "[--png F] [--json F] [--wrench-log F]]\n"
                   "  --loop      play the script back and forth until --seconds (a soak)\n"
                   "  --lockstep  haptic samples and physics steps in turn on simulated time,\n"
                   "              one thread: the same outcome on any machine load\n",
                   argv[0]);
      return false;
    }
  }
  if (o.physics_hz == 0.0) o.physics_hz = o.scene == "cavity" ? 500.0 : 1000.0;
  return o.seconds >= 0.0 && std::isfinite(o.seconds) && o.physics_hz >= 100.0 &&
         o.physics_hz <= 10000.0;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (!parse(argc, argv, options)) return 2;
  const std::string script_prefix = "script:";
  const bool script = options.device.rfind(script_prefix, 0) == 0;
  if ((options.headless || options.loop) && !script) {
    std::fprintf(stderr, "--headless and --loop need --device script:FILE\n");
    return 2;
  }
  if (options.lockstep && !options.headless) {
    std::fprintf(stderr, "--lockstep needs --headless\n");
    return 2;
  }
  std::atomic<double> sim_clock{0.0};  // --lockstep: the script's clock
  std::string error;
  std::unique_ptr<sc::demo::Device> device;
  if (script) {
    sc::demo::ScriptPlayback playback;
    playback.ping_pong = options.loop;
    playback.log_wrenches = !options.wrench_log.empty();  // else memory would grow with time
    if (options.lockstep) playback.clock = [&sim_clock] { return sim_clock.load(); };
    device =
        sc::demo::makeScriptDevice(options.device.substr(script_prefix.size()), error, playback);
  } else {
    device = sc::demo::makeDevice(options.device, error);
  }
  if (!device) {
    std::fprintf(stderr, "device: %s\n", error.c_str());
    return 2;
  }
  Demo demo(options, std::move(device));
  sc::demo::ViewerCallbacks cb;
  cb.collect = [&](std::vector<sc::demo::DrawItem>& items) { demo.collect(items); };
  cb.overlay = [&] { return demo.overlay(); };
  if (options.headless) {
    const double seconds = options.seconds > 0 ? options.seconds : demo.defaultSeconds();
    if (options.lockstep) {
      demo.runLockstep(seconds, sim_clock);
    } else {
      demo.start();
      std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
      demo.stop();
    }
    const std::string metrics = demo.json();
    if (!sc::demo::emitMetrics(metrics, options.json)) return 1;
    const sc::demo::WrenchLog* log = sc::demo::wrenchLogOf(demo.device());
    if (!options.wrench_log.empty() && log != nullptr) {
      FILE* f = std::fopen(options.wrench_log.c_str(), "w");
      if (f == nullptr) return 1;
      std::fprintf(f, "# t fx fy fz tx ty tz (reaction rendered to the device)\n");
      for (std::size_t i = 0; i < log->t.size(); ++i) {
        const sc::demo::Wrench& w = log->wrench[i];
        std::fprintf(f, "%.6f %.6g %.6g %.6g %.6g %.6g %.6g\n", log->t[i], w.force[0], w.force[1],
                     w.force[2], w.torque[0], w.torque[1], w.torque[2]);
      }
      std::fclose(f);
    }
    if (!options.png.empty() &&
        !sc::demo::renderToPng(argc, argv, cb, demo.targetY(), demo.distance(), options.png))
      return 1;
    return 0;
  }
  bool attached = false;
  cb.step = [&] {
    if (!attached) {  // the window exists now: window-fed devices take their events
      demo.device().attachWindow();
      attached = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));  // about 60-100 frames per second
  };
  cb.key = [&](unsigned char k) { demo.device().key(k); };
  demo.start();
  sc::demo::runViewer(argc, argv, "SmartCollision haptic coupling", cb, demo.targetY(),
                      demo.distance());
  return 0;
}
