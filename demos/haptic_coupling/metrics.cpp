// SPDX-License-Identifier: MIT
#include "metrics.h"

#include <cstdio>

#include "../common/cli.h"

namespace sc::demo::haptic {

double PeriodHistogram::percentile(double p) const {
  if (count_ == 0) return 0.0;
  const long rank = std::min(count_ - 1, long(p * double(count_ - 1) + 0.5));
  long seen = 0;
  for (std::size_t i = 0; i < bins_.size(); ++i) {
    seen += bins_[i];
    if (seen > rank) return std::min(max_, (double(i) + 0.5) * 1e-6);
  }
  return max_;
}

bool finite(const sc::haptics::BodyState& s) {
  return s.pose.position.allFinite() && s.pose.orientation.coeffs().allFinite() &&
         s.linear_velocity.allFinite() && s.angular_velocity.allFinite();
}

bool finite(const sc::haptics::CouplingWrench& w) {
  return w.force.allFinite() && w.torque.allFinite();
}

double kineticEnergy(const btRigidBody& b) {
  const btVector3 v = b.getLinearVelocity();
  const btVector3 w = b.getWorldTransform().getBasis().transpose() * b.getAngularVelocity();
  const btVector3 inv_i = b.getInvInertiaDiagLocal();
  double e = b.getInvMass() > 0 ? 0.5 * double(v.length2()) / double(b.getInvMass()) : 0.0;
  for (int k = 0; k < 3; ++k)
    if (inv_i[k] > 0) e += 0.5 * double(w[k]) * double(w[k]) / double(inv_i[k]);
  return e;
}

std::string metricsJson(const LoopMetrics& m, const RunReport& r) {
  const sc::haptics::CouplingGains& g = r.gains;
  const sc::haptics::CouplingEnergyMonitor& monitor = *r.monitor;
  const sc::haptics::BodyState& s = r.final_state;
  const Vec3& rv = r.final_rotation_vector;
  // Nominal bound: one haptic period of device motion, one physics step of the body.
  const double jump_bound =
      sc::haptics::forceJumpBound(g, r.max_device_speed, r.haptic_dt, r.physics_dt);
  const double impact_bound =
      sc::haptics::impactJumpBound(g, r.max_device_speed, r.haptic_dt, r.physics_dt);
  const long haptic = m.haptic_count.load(), physics = m.physics_count.load();
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
      r.scene.c_str(), r.device, m.lockstep ? "lockstep" : "realtime",
      m.haptic_fifo.load() ? "true" : "false", m.wall_seconds, r.tool_triangles, r.fixed_triangles,
      m.elapsed, m.periods.count() + 1, m.elapsed > 0 ? double(haptic) / m.elapsed : 0.0,
      1e3 * m.periods.percentile(0.5), 1e3 * m.periods.percentile(0.99), 1e3 * m.periods.max(),
      physics, m.elapsed > 0 ? double(physics) / m.elapsed : 0.0,
      physics ? 1e3 * m.step_seconds / double(physics) : 0.0, 1e3 * m.step_max, m.steps_over_period,
      g.linear_stiffness, g.linear_damping, g.angular_stiffness, g.angular_damping, g.max_force,
      g.max_torque, r.passivity.body_margin, r.passivity.required_device_damping, m.max_jump,
      jump_bound, m.max_jump_ratio, m.impacts, m.max_impact_jump, impact_bound, m.max_impact_ratio,
      m.max_jump_any, m.unchecked_samples, m.max_coupling_force, monitor.generated(),
      monitor.maxGenerated(), monitor.bodyWork(), monitor.deviceWork(), monitor.springEnergy(),
      monitor.kineticEnergyChange(), m.max_kinetic, m.non_finite_steps, m.non_finite_samples,
      m.rss_after_1s_kb, m.rss_after_60s_kb, residentKb(), std::max(peakResidentKb(), residentKb()),
      m.max_depth.load(), s.pose.position.x(), s.pose.position.y(), s.pose.position.z(), rv.x(),
      rv.y(), rv.z(), r.inserted_depth, r.inside ? "true" : "false");
  return buf;
}

}  // namespace sc::demo::haptic
