// SPDX-License-Identifier: MIT
// Virtual coupling: a 6-DOF spring-damper between a haptic device's pose and one
// Bullet rigid body (manual 9-10.3), its gains, its passivity check, an energy
// monitor, and the pose scripts that replay a recorded device trajectory.
//
// The coupling wrench on the body is
//   F   = k_t (x_dev - x_body) - b_t v_body
//   tau = k_r rotvec(q_dev q_body^-1) - b_r w_body
// with the spring part saturated at max_force / max_torque (a saturated spring is
// still conservative: its potential grows linearly beyond the saturation) and the
// damper part scaled down, never reversed, when the sum would exceed the limit. The
// device is given the reaction, -F and -tau, times CouplingGains::render_scale.
//
// Gains (designCouplingGains): the coupling is a mass-spring of natural period
// `period_steps` physics steps, omega = 2 pi / (period_steps T_p),
//   k_t = m omega^2,  b_t = 2 zeta sqrt(k_t m),
//   k_r = I_min omega^2,  b_r = 2 zeta omega sqrt(I_min I_max).
// Passivity bound (Colgate and Schenkel, sampled-data spring, zero-order hold): a
// virtual spring K with virtual damper B, sampled with period T, coupled to a
// damper b, is passive when
//   b > K T / 2 + |B|.
// It is checked twice (checkPassivity):
//  * body side: the spring is held over a physics step T_p and the damper b_t acts on
//    the body velocity, with no other virtual damper: b_t > k_t T_p / 2 (same for
//    rotation); with the design above this is omega T_p < 4 zeta.
//  * device side: the device sees render_scale k_t sampled at the haptic period T_h
//    and no virtual damper on its own velocity, so its physical damping b_dev must
//    satisfy b_dev > render_scale k_t T_h / 2. When b_dev is given, render_scale is
//    lowered until this holds with a 20 % margin.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <string>
#include <vector>

#include "smartcollision/types.h"

namespace sc::haptics {

/// A pose in world coordinates (device or body centre of mass).
struct CouplingPose {
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
};

/// The state of the coupled body the wrench is computed from.
struct BodyState {
  CouplingPose pose;
  Vec3 linear_velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
};

/// The body's centre-of-mass pose and velocities.
BodyState bodyStateOf(const btRigidBody& body);

struct CouplingWrench {
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
  bool clamped = false;  ///< a limit scaled the wrench down
};

struct CouplingGains {
  double linear_stiffness = 0.0;   ///< k_t [N/m]
  double linear_damping = 0.0;     ///< b_t [N s/m]
  double angular_stiffness = 0.0;  ///< k_r [N m/rad]
  double angular_damping = 0.0;    ///< b_r [N m s/rad]
  double max_force = 0.0;          ///< [N]; <= 0: no limit
  double max_torque = 0.0;         ///< [N m]; <= 0: no limit
  double render_scale = 1.0;       ///< fraction of the reaction sent to the device
};

struct CouplingDesign {
  double physics_dt = 1e-3;                 ///< T_p [s]
  double haptic_dt = 1e-3;                  ///< T_h [s]
  double period_steps = 20.0;               ///< coupling natural period in physics steps (>= 2)
  double damping_ratio = 1.0;               ///< zeta
  double max_acceleration = 60.0;           ///< max_force = m * this [m/s^2]
  double max_angular_acceleration = 600.0;  ///< max_torque = I_min * this [rad/s^2]
  double device_damping = 0.0;              ///< physical damping of the device [N s/m]; 0: unknown
  double device_angular_damping = 0.0;      ///< [N m s/rad]; 0: unknown
};

/// Gains for a body of mass `mass` and principal moments `inertia_min` <= `inertia_max`.
CouplingGains designCouplingGains(double mass, double inertia_min, double inertia_max,
                                  const CouplingDesign& design);
/// The same from a dynamic body's mass and local inertia.
CouplingGains designCouplingGains(const btRigidBody& body, const CouplingDesign& design);

struct PassivityReport {
  bool body_side = false;    ///< b_t > k_t T_p/2 and b_r > k_r T_p/2
  double body_margin = 0.0;  ///< min(b_t / (k_t T_p/2), b_r / (k_r T_p/2)); > 1 passes
  /// Physical device damping the device side needs: render_scale k T_h / 2.
  double required_device_damping = 0.0;
  double required_device_angular_damping = 0.0;
  /// Known device damping above the requirement; false when it is unknown (0).
  bool device_side = false;
};

PassivityReport checkPassivity(const CouplingGains& gains, const CouplingDesign& design);

/// Documented bound on the change of the coupling force between two consecutive
/// haptic samples taken `device_interval` apart, between which the body advanced
/// `body_interval` of simulated time (its physics steps times T_p), device and body
/// moving at most `max_speed`:
///   k_t v (device_interval + body_interval)  spring: |d(x_dev - x_body)|
/// + 0.1 max_force                            damper b_t dv: the body's velocity change
///                                            while it slides or moves freely (smooth:
///                                            at most a tenth of the limit).
/// At 1 kHz in lockstep (both intervals 1 ms) and v = 0.1 m/s: 2 k_t v T + 0.1 max_force.
/// It does not hold at an impact: see impactJumpBound.
double forceJumpBound(const CouplingGains& gains, double max_speed, double device_interval,
                      double body_interval);

/// The same bound for the samples that follow a contact's onset: the contact model
/// stops an approach within a step or two (restitution 0, critically damped), so the
/// damper's term is the whole b_t v instead of 0.1 max_force:
///   k_t v (device_interval + body_interval) + b_t v.
double impactJumpBound(const CouplingGains& gains, double max_speed, double device_interval,
                       double body_interval);

/// Axis times angle of q (shortest way, angle in [0, pi]).
Vec3 rotationVector(const Quat& q);

class VirtualCoupling {
 public:
  explicit VirtualCoupling(const CouplingGains& gains) : gains_(gains) {}
  const CouplingGains& gains() const { return gains_; }

  /// The wrench on the body (limits applied).
  CouplingWrench wrenchOnBody(const CouplingPose& device, const BodyState& body) const;
  /// The wrench for the device: -render_scale times wrenchOnBody.
  CouplingWrench reaction(const CouplingPose& device, const BodyState& body) const;
  /// Computes the wrench on `body`, adds it to the body's total force and torque and
  /// returns it. Call once before each stepSimulation(dt, 1, dt): Bullet clears the
  /// forces after every stepSimulation, so one substep per call keeps it per substep.
  CouplingWrench apply(const CouplingPose& device, btRigidBody& body) const;

  /// Potential energy of the (saturated) springs between `device` and `body`.
  double springEnergy(const CouplingPose& device, const CouplingPose& body) const;

 private:
  CouplingGains gains_;
};

/// Energy balance of the coupling over a run, one record per physics step:
///   generated = sum_k [ W_body,k + U(dev_k, body_k+1) - U(dev_k, body_k) ]
/// where W_body,k is the work of the applied wrench over the body's displacement in
/// step k (force held, as Bullet integrates it) and U the spring energy with the
/// device held at its pose of step k. Device motion between steps is the device's
/// work (deviceWork()). In continuous time generated = -(damper dissipation) <= 0;
/// a sampled spring adds 1/2 k |dx|^2 per step, which the damper must outweigh
/// (body-side passivity bound). generated > 0 means the coupling created energy.
class CouplingEnergyMonitor {
 public:
  /// Before stepSimulation: the device pose used, the body state, the applied wrench.
  void beforeStep(const VirtualCoupling& coupling, const CouplingPose& device,
                  const btRigidBody& body, const CouplingWrench& applied);
  /// After stepSimulation.
  void afterStep(const btRigidBody& body);

  double generated() const { return generated_; }
  double maxGenerated() const { return max_generated_; }  ///< running maximum
  double bodyWork() const { return body_work_; }          ///< work of the coupling on the body
  double deviceWork() const { return device_work_; }      ///< work of the device on the spring
  double springEnergy() const { return spring_energy_; }  ///< now
  /// Kinetic energy of the body now minus at the first record.
  double kineticEnergyChange() const { return kinetic_ - kinetic_start_; }
  long steps() const { return steps_; }

 private:
  static double kineticEnergy(const btRigidBody& body);

  const VirtualCoupling* coupling_ = nullptr;
  CouplingPose device_, previous_device_;
  CouplingPose body_before_;
  CouplingWrench applied_;
  bool pending_ = false, has_previous_ = false;
  double generated_ = 0.0, max_generated_ = 0.0, body_work_ = 0.0, device_work_ = 0.0;
  double spring_energy_ = 0.0, kinetic_ = 0.0, kinetic_start_ = 0.0;
  long steps_ = 0;
};

/// One line of a pose script.
struct PoseSample {
  double t = 0.0;
  CouplingPose pose;
};

/// A recorded device trajectory: text lines `t x y z qw qx qy qz` (seconds, metres,
/// unit quaternion; normalised on reading), times strictly increasing; '#' starts a
/// comment, blank lines are skipped. Sampled with linear interpolation of positions
/// and slerp of orientations, held at both ends.
class PoseScript {
 public:
  /// InvalidArgument naming the line and what is wrong (count of numbers, a
  /// non-number, non-finite value, zero quaternion, time not increasing, no sample).
  static Result<PoseScript> parse(const std::string& text);
  /// File error when the file cannot be read, else as parse.
  static Result<PoseScript> load(const std::string& path);

  CouplingPose sample(double t) const;
  double duration() const { return samples_.empty() ? 0.0 : samples_.back().t; }
  const std::vector<PoseSample>& samples() const { return samples_; }

 private:
  std::vector<PoseSample> samples_;
};

}  // namespace sc::haptics
