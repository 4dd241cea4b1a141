// SPDX-License-Identifier: MIT
// Virtual coupling, its gains and passivity check, the energy monitor and pose scripts.
#include "smartcollision/haptics/virtual_coupling.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace sc::haptics {

namespace {


Vec3 toVec(const btVector3& v) { return Vec3(double(v.x()), double(v.y()), double(v.z())); }
btVector3 toBt(const Vec3& v) {
  return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
}

Quat toQuat(const btQuaternion& q) {
  return Quat(double(q.w()), double(q.x()), double(q.y()), double(q.z())).normalized();
}

/// Spring part k e saturated at `limit` (<= 0: none).
Vec3 saturatedSpring(double k, const Vec3& e, double limit) {
  Vec3 f = k * e;
  const double n = f.norm();
  if (limit > 0.0 && n > limit) f *= limit / n;
  return f;
}

/// Potential of the saturated spring at stretch |e|.
double saturatedPotential(double k, double stretch, double limit) {
  if (k <= 0.0) return 0.0;
  if (limit <= 0.0 || k * stretch <= limit) return 0.5 * k * stretch * stretch;
  const double knee = limit / k;
  return 0.5 * limit * knee + limit * (stretch - knee);
}

/// spring + alpha damper with the largest alpha in [0, 1] whose norm is <= limit
/// (|spring| <= limit already). Sets `clamped` when alpha < 1.
Vec3 limitDamper(const Vec3& spring, const Vec3& damper, double limit, bool& clamped) {
  const Vec3 sum = spring + damper;
  if (limit <= 0.0 || sum.squaredNorm() <= limit * limit) return sum;
  clamped = true;
  const double dd = damper.squaredNorm();
  if (dd <= 0.0) return spring;
  const double ad = spring.dot(damper);
  const double c = spring.squaredNorm() - limit * limit;  // <= 0
  const double disc = std::max(0.0, ad * ad - dd * c);
  const double alpha = std::clamp((-ad + std::sqrt(disc)) / dd, 0.0, 1.0);
  return spring + alpha * damper;
}

bool finiteVec(const Vec3& v) { return v.allFinite(); }

}  // namespace

BodyState bodyStateOf(const btRigidBody& body) {
  BodyState s;
  const btTransform& t = body.getCenterOfMassTransform();
  s.pose.position = toVec(t.getOrigin());
  s.pose.orientation = toQuat(t.getRotation());
  s.linear_velocity = toVec(body.getLinearVelocity());
  s.angular_velocity = toVec(body.getAngularVelocity());
  return s;
}

CouplingGains designCouplingGains(double mass, double inertia_min, double inertia_max,
                                  const CouplingDesign& design) {
  CouplingGains g;
  const double period = std::max(2.0, design.period_steps) * design.physics_dt;
  const double omega = 2.0 * kPi / period;
  const double zeta = std::max(0.0, design.damping_ratio);
  const double i_min = std::max(1e-12, std::min(inertia_min, inertia_max));
  const double i_max = std::max(i_min, inertia_max);
  g.linear_stiffness = mass * omega * omega;
  g.linear_damping = 2.0 * zeta * std::sqrt(g.linear_stiffness * mass);
  g.angular_stiffness = i_min * omega * omega;
  g.angular_damping = 2.0 * zeta * omega * std::sqrt(i_min * i_max);
  g.max_force = mass * design.max_acceleration;
  g.max_torque = i_min * design.max_angular_acceleration;
  g.render_scale = 1.0;
  // Device side: b_dev > s k T_h / 2 with a 20 % margin.
  const double th = design.haptic_dt;
  if (design.device_damping > 0.0 && g.linear_stiffness * th > 0.0)
    g.render_scale =
        std::min(g.render_scale, design.device_damping / (1.2 * 0.5 * g.linear_stiffness * th));
  if (design.device_angular_damping > 0.0 && g.angular_stiffness * th > 0.0)
    g.render_scale = std::min(
        g.render_scale, design.device_angular_damping / (1.2 * 0.5 * g.angular_stiffness * th));
  return g;
}

CouplingGains designCouplingGains(const btRigidBody& body, const CouplingDesign& design) {
  const double inv_mass = double(body.getInvMass());
  const double mass = inv_mass > 0.0 ? 1.0 / inv_mass : 0.0;
  const btVector3 inv = body.getInvInertiaDiagLocal();
  double i_min = 0.0, i_max = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double i = inv[k] > 0 ? 1.0 / double(inv[k]) : 0.0;
    if (i <= 0.0) continue;
    i_min = i_min > 0.0 ? std::min(i_min, i) : i;
    i_max = std::max(i_max, i);
  }
  return designCouplingGains(mass, i_min, i_max, design);
}

PassivityReport checkPassivity(const CouplingGains& g, const CouplingDesign& design) {
  PassivityReport r;
  const double tp = design.physics_dt, th = design.haptic_dt;
  const double need_t = 0.5 * g.linear_stiffness * tp, need_r = 0.5 * g.angular_stiffness * tp;
  const double mt = need_t > 0.0 ? g.linear_damping / need_t : kInfinity;
  const double mr = need_r > 0.0 ? g.angular_damping / need_r : kInfinity;
  r.body_margin = std::min(mt, mr);
  r.body_side = r.body_margin > 1.0;
  r.required_device_damping = 0.5 * g.render_scale * g.linear_stiffness * th;
  r.required_device_angular_damping = 0.5 * g.render_scale * g.angular_stiffness * th;
  r.device_side = design.device_damping > r.required_device_damping &&
                  design.device_angular_damping > r.required_device_angular_damping;
  return r;
}

double forceJumpBound(const CouplingGains& gains, double max_speed, double device_interval,
                      double body_interval) {
  return gains.linear_stiffness * max_speed * (device_interval + body_interval) +
         0.1 * gains.max_force;
}

double impactJumpBound(const CouplingGains& gains, double max_speed, double device_interval,
                       double body_interval) {
  return gains.linear_stiffness * max_speed * (device_interval + body_interval) +
         gains.linear_damping * max_speed;
}

Vec3 rotationVector(const Quat& q_in) {
  Quat q = q_in.normalized();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // shortest way
  const Vec3 v = q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;  // small angle: angle ~ 2 s
  const double angle = 2.0 * std::atan2(s, q.w());
  return v * (angle / s);
}

CouplingWrench VirtualCoupling::wrenchOnBody(const CouplingPose& device,
                                             const BodyState& body) const {
  CouplingWrench w;
  const Vec3 e = device.position - body.pose.position;
  const Vec3 spring = saturatedSpring(gains_.linear_stiffness, e, gains_.max_force);
  const Vec3 damper = -gains_.linear_damping * body.linear_velocity;
  w.force = limitDamper(spring, damper, gains_.max_force, w.clamped);
  if (gains_.max_force > 0.0 && (gains_.linear_stiffness * e).norm() > gains_.max_force)
    w.clamped = true;
  const Vec3 theta = rotationVector(device.orientation * body.pose.orientation.conjugate());
  const Vec3 rspring = saturatedSpring(gains_.angular_stiffness, theta, gains_.max_torque);
  const Vec3 rdamper = -gains_.angular_damping * body.angular_velocity;
  w.torque = limitDamper(rspring, rdamper, gains_.max_torque, w.clamped);
  if (gains_.max_torque > 0.0 && (gains_.angular_stiffness * theta).norm() > gains_.max_torque)
    w.clamped = true;
  if (!finiteVec(w.force) || !finiteVec(w.torque)) w = CouplingWrench();
  return w;
}

CouplingWrench VirtualCoupling::reaction(const CouplingPose& device, const BodyState& body) const {
  CouplingWrench w = wrenchOnBody(device, body);
  w.force *= -gains_.render_scale;
  w.torque *= -gains_.render_scale;
  return w;
}

CouplingWrench VirtualCoupling::apply(const CouplingPose& device, btRigidBody& body) const {
  const CouplingWrench w = wrenchOnBody(device, bodyStateOf(body));
  body.applyCentralForce(toBt(w.force));
  body.applyTorque(toBt(w.torque));
  body.activate();
  return w;
}

double VirtualCoupling::springEnergy(const CouplingPose& device, const CouplingPose& body) const {
  const double stretch = (device.position - body.position).norm();
  const double angle = rotationVector(device.orientation * body.orientation.conjugate()).norm();
  return saturatedPotential(gains_.linear_stiffness, stretch, gains_.max_force) +
         saturatedPotential(gains_.angular_stiffness, angle, gains_.max_torque);
}

double CouplingEnergyMonitor::kineticEnergy(const btRigidBody& body) {
  if (body.getInvMass() <= 0) return 0.0;
  double e = 0.5 * double(body.getLinearVelocity().length2()) / double(body.getInvMass());
  const btVector3 w =
      body.getCenterOfMassTransform().getBasis().transpose() * body.getAngularVelocity();
  const btVector3 inv = body.getInvInertiaDiagLocal();
  for (int k = 0; k < 3; ++k)
    if (inv[k] > 0) e += 0.5 * double(w[k] * w[k] / inv[k]);
  return e;
}

void CouplingEnergyMonitor::beforeStep(const VirtualCoupling& coupling, const CouplingPose& device,
                                       const btRigidBody& body, const CouplingWrench& applied) {
  coupling_ = &coupling;
  body_before_ = bodyStateOf(body).pose;
  if (steps_ == 0 && !pending_) kinetic_start_ = kinetic_ = kineticEnergy(body);
  if (has_previous_)
    device_work_ += coupling.springEnergy(device, body_before_) -
                    coupling.springEnergy(previous_device_, body_before_);
  device_ = device;
  applied_ = applied;
  pending_ = true;
}

void CouplingEnergyMonitor::afterStep(const btRigidBody& body) {
  if (!pending_ || coupling_ == nullptr) return;
  pending_ = false;
  const CouplingPose after = bodyStateOf(body).pose;
  const Vec3 dx = after.position - body_before_.position;
  const Vec3 dtheta = rotationVector(after.orientation * body_before_.orientation.conjugate());
  const double work = applied_.force.dot(dx) + applied_.torque.dot(dtheta);
  const double u_before = coupling_->springEnergy(device_, body_before_);
  spring_energy_ = coupling_->springEnergy(device_, after);
  body_work_ += work;
  generated_ += work + spring_energy_ - u_before;
  max_generated_ = std::max(max_generated_, generated_);
  kinetic_ = kineticEnergy(body);
  previous_device_ = device_;
  has_previous_ = true;
  ++steps_;
}

Result<PoseScript> PoseScript::parse(const std::string& text) {
  PoseScript script;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  auto fail = [&](const std::string& what) {
    return Status(ErrorCode::InvalidArgument,
                  "pose script line " + std::to_string(number) + ": " + what);
  };
  while (std::getline(in, line)) {
    ++number;
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream fields(line);
    std::vector<double> values;
    std::string token;
    while (fields >> token) {
      std::size_t used = 0;
      double v = 0.0;
      try {
        v = std::stod(token, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != token.size()) return fail("'" + token + "' is not a number");
      if (!std::isfinite(v)) return fail("non-finite value '" + token + "'");
      values.push_back(v);
    }
    if (values.empty()) continue;
    if (values.size() != 8)
      return fail("expected 8 numbers 't x y z qw qx qy qz', got " + std::to_string(values.size()));
    PoseSample s;
    s.t = values[0];
    s.pose.position = Vec3(values[1], values[2], values[3]);
    const Quat q(values[4], values[5], values[6], values[7]);
    if (q.norm() < 1e-9) return fail("zero quaternion");
    s.pose.orientation = q.normalized();
    if (!script.samples_.empty() && !(s.t > script.samples_.back().t))
      return fail("time " + std::to_string(s.t) + " does not increase");
    script.samples_.push_back(s);
  }
  if (script.samples_.empty())
    return Status(ErrorCode::InvalidArgument, "pose script has no sample");
  return script;
}

Result<PoseScript> PoseScript::load(const std::string& path) {
  // Opening a FIFO for reading would wait for a writer: only regular files are read.
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    return Status(ErrorCode::File, "pose script " + path + " is not a regular file");
  std::ifstream f(path);
  if (!f) return Status(ErrorCode::File, "cannot read pose script " + path);
  std::ostringstream text;
  text << f.rdbuf();
  Result<PoseScript> r = parse(text.str());
  if (!r.ok()) return Status(r.status().code(), path + ": " + r.status().message());
  return r;
}

CouplingPose PoseScript::sample(double t) const {
  if (samples_.empty()) return {};
  if (t <= samples_.front().t) return samples_.front().pose;
  if (t >= samples_.back().t) return samples_.back().pose;
  const auto it = std::upper_bound(samples_.begin(), samples_.end(), t,
                                   [](double v, const PoseSample& s) { return v < s.t; });
  const PoseSample& b = *it;
  const PoseSample& a = *(it - 1);
  const double u = (t - a.t) / (b.t - a.t);
  CouplingPose p;
  p.position = (1.0 - u) * a.pose.position + u * b.pose.position;
  p.orientation = a.pose.orientation.slerp(u, b.pose.orientation).normalized();
  return p;
}

}  // namespace sc::haptics
