// SPDX-License-Identifier: MIT
// Settings of the Bullet plugin: contact model, the potential model's stiffness and
// damping rule (world defaults, per-body overrides), and the core's query settings.
#pragma once

#include <cstdint>

#include "smartcollision/settings.h"

namespace sc::bullet {

/// How a penetrating pair acts on its bodies; switchable at run time, per world.
enum class ContactModel : std::uint8_t {
  Potential,  ///< manual 5.9: the spring-damper of ContactSettings at the contact polygon (default)
  Manifold,   ///< the result's contacts go to a persistent manifold for Bullet's solver
};

/// Spring-damper of the potential model, integrated implicitly by Bullet's solver as
/// rows at the contact points of a pair (docs/bullet.md). With omega =
/// 2 pi / (contact_period_steps dt): by default (contact_stiffness 0) each row is rigid
/// at the velocity level and recovers depth at the rate of a spring-damper of
/// frequency omega and ratio damping_ratio relative to the row's own effective mass
/// (erp = dt omega / (dt omega + 2 zeta)): no sag under any load or mass ratio beyond
/// what the solver's iterations leave. A contact_stiffness set here is a true implicit
/// spring kT spread over the pair's rows, honoured as given (statics: sag = load / kT).
struct ContactSettings {
  double contact_period_steps = 10.0;  ///< natural period of a contact in substeps (>= 1)
  double damping_ratio = 1.0;          ///< zeta; 1 = critical (>= 0)
  double contact_stiffness = 0.0;      ///< kT [N/m]; 0 = derived
  /// kR [N m/rad]; 0 = derived (I omega^2). Weighs rotation against translation in
  /// the Mix rotation mode; the rows' torque is the contact polygon's (docs/bullet.md).
  double contact_torque_stiffness = 0.0;
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
  /// plugin sets force_stiffness / torque_stiffness per pair from the contact spring
  /// (they weigh Mix).
  SceneSettings query = defaultQuerySettings();
  /// A pair's tolerance is at most this fraction of its smaller body's size (half the
  /// diagonal of its model's bounds, plus a sphere's or capsule's radius): a mesh body
  /// rests about the tolerance deep, so small bodies rest as shallow, for their size,
  /// as large ones (a 1 cm cow: 0.11 mm, not the absolute 1 mm). 0 = the tolerance alone.
  double relative_tolerance = 0.02;
  /// Pairs that start intersecting deeper than the spring can take (its energy
  /// 1/2 k d^2 above 1/2 m_red v^2, i.e. d > v / omega) are pushed apart at overlap /
  /// contact period, at most this speed v [m/s]: along their depth's normal when the
  /// core gives one, else along the smallest overlap axis of their AABBs. Shallower
  /// ones (bodies spawned touching) get the contact model at once.
  double recovery_speed = 1.0;
};

/// Ok, or InvalidArgument naming the first bad field.
Status validate(const ContactSettings& settings);
Status validate(const PluginSettings& settings);

}  // namespace sc::bullet
