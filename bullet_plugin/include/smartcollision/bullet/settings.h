// SPDX-License-Identifier: MIT
// Settings of the Bullet plugin: contact model, the potential model's stiffness and
// damping rule (world defaults, per-body overrides), and the core's query settings.
#pragma once

#include <cstdint>

#include "smartcollision/settings.h"

namespace sc::bullet {

/// How a penetrating pair acts on its bodies; switchable at run time, per world.
enum class ContactModel : std::uint8_t {
  Potential,  ///< manual 5.9: F = -kT TPDV, tau = -kR RPDV per body, plus damping (default)
  Manifold,   ///< the result's contacts go to a persistent manifold for Bullet's solver
};

/// Spring-damper of the potential model. Zero stiffness means "derive": with the
/// pair's reduced mass m (moment of inertia I) and the substep dt,
///   omega = 2 pi / (contact_period_steps dt),  kT = m omega^2,  kR = I omega^2,
///   cT = 2 damping_ratio sqrt(kT m_d),         cR = 2 damping_ratio sqrt(kR I),
/// m_d = m, or the body's own mass for the heavier body of the pair. The spring is
/// explicit (exact statics), the damping implicit; k is clamped to m / dt^2 for
/// stability. See docs/bullet.md.
struct ContactSettings {
  double contact_period_steps = 10.0;  ///< natural period of a contact in substeps (>= 1)
  double damping_ratio = 1.0;          ///< zeta; 1 = critical (>= 0)
  double force_stiffness = 0.0;        ///< kT [N/m]; 0 = derived
  double torque_stiffness = 0.0;       ///< kR [N m/rad]; 0 = derived
  double friction_scale = 1.0;         ///< scales Bullet's combined friction (potential model)
};

/// The core's query settings the plugin starts from: the core's defaults, rotation
/// mode Input (translational depth; Mix/Free are settable, see docs/bullet.md), and
/// resolve_initial_intersection on (pairs first seen intersecting get a depth).
SceneSettings defaultQuerySettings();

struct PluginSettings {
  ContactModel model = ContactModel::Potential;
  ContactSettings contact;  ///< world default; bodies may override (Plugin::setBodySettings)
  /// Tolerance, iterations and rotation mode of the dynamic penetration depth. The
  /// plugin sets force_stiffness / torque_stiffness per pair (they weigh Mix).
  SceneSettings query = defaultQuerySettings();
  /// Pairs that start intersecting deeper than the spring can take (its energy
  /// 1/2 k d^2 above 1/2 m_red v^2, i.e. d > v / omega) are pushed apart at overlap /
  /// contact period, at most this speed v [m/s]: along their depth's normal when the
  /// core gives one, else along the smallest overlap axis of their AABBs. Shallower
  /// ones (bodies spawned touching) get the contact model at once.
  double recovery_speed = 1.0;
};

/// Ok, or InvalidArgument naming the first bad field.
Status validate(const PluginSettings& settings);

}  // namespace sc::bullet
