// SPDX-License-Identifier: MIT
// The four rotation modes on rotational penetrations (manual 5.7-5.9): a bar turned
// into a box from a free pose (random cases) and the manual's Fig. 5-11 bar wedged in
// a slot, which no translation can free. Each mode's converged result is compared.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "penetration/result_invariants.h"
#include "preprocess/convex_hull.h"
#include "smartcollision/collision.h"
#include "support/brute_force.h"
#include "support/placements.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

constexpr int kCases = caseCount(300, 30);
constexpr double kTolerance = 1e-3;
const double kPiValue = std::acos(-1.0);
/// Updates at the same goal until a mode's result changes by at most 1e-12 (the proxy
/// turns by at most Cs eps per iteration, so a larger turn takes several updates).
constexpr int kMaxRepeats = 40;
/// Documented slack of "MIX's potential P <= the others' best": relative, plus the
/// first-order change of P for one tolerance eps of translation, kT eps |D| (the
/// contact pose is only exact to eps).
constexpr double kMixRelativeSlack = 1e-3;

constexpr std::array<RotationMode, 4> kModes = {RotationMode::None, RotationMode::Input,
                                                RotationMode::Free, RotationMode::Mix};
enum { kNone, kInput, kFree, kMix };

double potential(const DirectedResult& r, const SceneSettings& s) {
  return 0.5 * s.force_stiffness * r.tpdv.squaredNorm() +
         0.5 * s.torque_stiffness * r.rpdv.squaredNorm();
}

/// Target and opponent as groups of boxes, with their meshes for brute-force checks.
struct Scene {
  std::vector<ModelPtr> models;
  std::vector<Part> target_parts, opponent_parts;
  std::vector<MeshData> target_meshes, opponent_meshes;
  std::vector<Rigid> target_offsets, opponent_offsets;

  void add(bool target, const Vec3& half, const Vec3& offset) {
    models.push_back(boxModel(half));
    const Rigid at{Mat3::Identity(), offset};
    (target ? target_parts : opponent_parts).push_back({models.back().get(), at, 0});
    (target ? target_meshes : opponent_meshes).push_back(boxMesh(half));
    (target ? target_offsets : opponent_offsets).push_back(at);
  }
  /// Deepest exact penetration depth over the (convex) box pairs, the target placed at
  /// `world_from_target`: the origin's depth in the hull of the Minkowski difference.
  double depth(const Rigid& world_from_target) const {
    double worst = 0.0;
    for (size_t i = 0; i < target_meshes.size(); ++i) {
      for (size_t j = 0; j < opponent_meshes.size(); ++j) {
        std::vector<Vec3> diff;
        for (const Vec3& p : target_meshes[i].vertices)
          for (const Vec3& q : opponent_meshes[j].vertices)
            diff.push_back(world_from_target * target_offsets[i] * p - opponent_offsets[j] * q);
        const auto hull = detail::convexHull(diff);
        EXPECT_TRUE(hull.ok());
        if (!hull.ok()) continue;
        double d = kInfinity;
        for (const Tri& f : hull.value().faces) {
          const auto& v = hull.value().vertices;
          const Vec3 n = (v[f[1]] - v[f[0]]).cross(v[f[2]] - v[f[0]]);
          if (n.norm() > 1e-300) d = std::min(d, n.normalized().dot(v[f[0]]));
        }
        worst = std::max(worst, d);
      }
    }
    return worst;
  }
  /// Brute-force surface distance of the target placed at `world_from_target`.
  double distance(const Rigid& world_from_target) const {
    double d = kInfinity;
    for (size_t i = 0; i < target_meshes.size(); ++i)
      for (size_t j = 0; j < opponent_meshes.size(); ++j)
        d = std::min(d, meshSurfaceDistance(target_meshes[i], world_from_target * target_offsets[i],
                                            opponent_meshes[j], opponent_offsets[j])
                            .distance);
    return d;
  }
};

/// Free pose, then the penetrating goal repeated until the result settles.
DirectedResult converged(const Scene& scene, const Placement& from, const Placement& to,
                         const SceneSettings& settings, int* repeats) {
  PairTracker tracker;
  DirectedResult out[2];
  const GroupView opponent{scene.opponent_parts.data(),
                           static_cast<int>(scene.opponent_parts.size()), Placement()};
  const auto run = [&](const Placement& p) {
    tracker.update({scene.target_parts.data(), static_cast<int>(scene.target_parts.size()), p},
                   opponent, {true, false}, settings, out);
  };
  run(from);
  EXPECT_EQ(out[0].code, ErrorCode::Ok);
  EXPECT_GT(out[0].distance, 0.0);
  DirectedResult last;
  for (*repeats = 0; *repeats < kMaxRepeats; ++*repeats) {
    run(to);
    if (*repeats > 0 && (out[0].tpdv - last.tpdv).norm() <= 1e-12 &&
        (out[0].rpdv - last.rpdv).norm() <= 1e-12)
      break;
    last = out[0];
  }
  return out[0];
}

/// The contact pose penetrates no box pair by more than the tolerance (exact depth).
double expectContactWithinTolerance(const Scene& scene, const DirectedResult& r) {
  const double d =
      scene.depth(placementOf(r.contact_orientation, r.contact_position).worldFromLocal());
  EXPECT_LE(d, kTolerance) << "contact pose penetrates by more than the tolerance";
  return d;
}

/// NONE keeps the orientation at the impact: it lies on the turn from `from` to `to`,
/// and the path pose there (the centre moved by the same fraction) is within the
/// tolerance of touching. Returns that pose's brute-force distance.
double expectNoneAtImpact(const Scene& scene, const Placement& from, const Placement& to,
                          const DirectedResult& none) {
  const double whole = Eigen::AngleAxisd(to.orientation * from.orientation.inverse()).angle();
  const double part =
      Eigen::AngleAxisd(none.contact_orientation * from.orientation.inverse()).angle();
  const double rest =
      Eigen::AngleAxisd(to.orientation * none.contact_orientation.inverse()).angle();
  EXPECT_NEAR(part + rest, whole, 1e-9) << "NONE's orientation is not on the path";
  const double s = whole > 1e-12 ? part / whole : 0.0;
  const Vec3 center = from.world_center + s * (to.world_center - from.world_center);
  const double gap = scene.distance(placementOf(none.contact_orientation, center).worldFromLocal());
  EXPECT_LE(gap, kTolerance) << "NONE's impact pose is " << gap << " from contact";
  return gap;
}

struct Figures {
  int penetrating = 0, input_rotated = 0, free_better = 0, mix_best = 0, max_repeats = 0;
  double worst_free_excess = 0.0, worst_mix_excess = 0.0, worst_none_gap = 0.0;
  double worst_contact_depth = 0.0;
};

/// The per-mode claims, for one free pose and one penetrating goal.
void checkModes(const Scene& scene, const Placement& from, const Placement& to,
                SceneSettings settings, Figures& fig) {
  std::array<DirectedResult, 4> r;
  std::array<int, 4> repeats_of{};
  for (int m = 0; m < 4; ++m) {
    settings.rotation_mode = kModes[m];
    int repeats = 0;
    r[m] = converged(scene, from, to, settings, &repeats);
    repeats_of[m] = repeats;
    fig.max_repeats = std::max(fig.max_repeats, repeats);
    SCOPED_TRACE(testing::Message() << "mode " << m);
    ASSERT_EQ(r[m].code, ErrorCode::Ok);
    const Status valid = detail::checkResult(r[m], to, Placement());
    EXPECT_TRUE(valid.ok()) << valid.message();
    ASSERT_TRUE(r[m].penetrating()) << "the goal intersects (brute force) but mode reports apart";
    fig.worst_contact_depth =
        std::max(fig.worst_contact_depth, expectContactWithinTolerance(scene, r[m]));
  }
  ++fig.penetrating;
  // NONE: the orientation at the impact on the path from the free pose.
  fig.worst_none_gap = std::max(fig.worst_none_gap, expectNoneAtImpact(scene, from, to, r[kNone]));
  // INPUT: a translation resolves whenever one does.
  if (r[kInput].rpdv.isZero(0.0)) {
    EXPECT_LE(Eigen::AngleAxisd(r[kInput].contact_orientation * to.orientation.inverse()).angle(),
              1e-9);
  } else {
    ++fig.input_rotated;
  }
  // FREE: translation first.
  const double free_excess = r[kFree].tpdv.norm() - r[kInput].tpdv.norm();
  fig.worst_free_excess = std::max(fig.worst_free_excess, free_excess);
  EXPECT_LE(free_excess, kTolerance);
  if (free_excess < -kTolerance) ++fig.free_better;
  // MIX: the potential's local minimum.
  const double p_mix = potential(r[kMix], settings);
  double p_best = kInfinity;
  for (int m : {kNone, kInput, kFree}) p_best = std::min(p_best, potential(r[m], settings));
  const double kt = settings.force_stiffness;
  const double slack = kMixRelativeSlack * p_best + kt * kTolerance * std::sqrt(2.0 * p_best / kt);
  const double mix_excess = (p_mix - p_best) / std::max(p_best, 1e-300);
  fig.worst_mix_excess = std::max(fig.worst_mix_excess, mix_excess);
  EXPECT_LE(p_mix, p_best + slack) << "MIX " << p_mix << " others' best " << p_best << [&] {
    testing::Message m;
    for (int k = 0; k < 4; ++k)
      m << "\n mode " << k << " |tpdv| " << r[k].tpdv.norm() << " |rpdv| " << r[k].rpdv.norm()
        << " repeats " << repeats_of[k];
    return m.GetString();
  }();
  if (p_mix < p_best) ++fig.mix_best;
}

TEST(RotationModes, BarTurnedIntoABox) {
  const std::uint64_t seed = 5711;
  SCOPED_TRACE(testing::Message() << "seed " << seed);
  Rng rng(seed);
  Figures fig;
  int cases = 0, attempts = 0;
  while (cases < kCases && attempts < 10 * kCases) {
    ++attempts;
    SCOPED_TRACE(testing::Message() << "attempt " << attempts);
    Scene scene;
    const double length = uniform(rng, 0.3, 1.0);
    scene.add(true, Vec3(length, uniform(rng, 0.02, 0.1), uniform(rng, 0.02, 0.1)), Vec3::Zero());
    scene.add(false, Vec3(1.5, 1.5, 0.5), Vec3::Zero());
    // A tilted bar above the box's top face (z = 0.5), lowered until it touches.
    const Quat q0 = Quat(Eigen::AngleAxisd(uniform(rng, -0.3, 0.3), randomDirection(rng))) *
                    Quat(Eigen::AngleAxisd(uniform(rng, 0.0, 2.0 * kPiValue), Vec3::UnitZ()));
    const Vec3 xy(uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5), 0.0);
    double lo = 0.0, hi = 2.0;  // lo intersecting, hi free
    for (int i = 0; i < 40; ++i) {
      const double mid = 0.5 * (lo + hi);
      const Rigid pose = placementOf(q0, xy + mid * Vec3::UnitZ()).worldFromLocal();
      (scene.distance(pose) > 0.0 ? hi : lo) = mid;
    }
    const Placement from = placementOf(q0, xy + (hi + 0.5 * kTolerance) * Vec3::UnitZ());
    // Turn about a random axis (plus a little sinking) so the bar's end dips in.
    const double dip = uniform(rng, 2.0, 8.0) * kTolerance;
    const Vec3 axis = randomDirection(rng);
    const Quat q1 = Quat(Eigen::AngleAxisd(dip / length, axis)) * q0;
    const Placement to =
        placementOf(q1, from.world_center - uniform(rng, 0.0, 2.0) * kTolerance * Vec3::UnitZ());
    if (scene.distance(to.worldFromLocal()) > 0.0) continue;  // turned away: not penetrating
    ++cases;
    SceneSettings settings;
    settings.tolerance = kTolerance;
    settings.torque_stiffness = uniform(rng, 0.1, 1.0) * length * length;
    checkModes(scene, from, to, settings, fig);
    if (HasFatalFailure()) return;
  }
  std::printf(
      "[ rotation modes ] bar into box: %d cases (%d attempts); INPUT rotated in %d; FREE "
      "|TPDV| - INPUT's <= %.3g tol (smaller by > tol in %d); MIX potential excess over the "
      "others' best <= %.3g relative (strictly best in %d); NONE impact pose within %.3g tol "
      "of contact; contact depth "
      "<= %.3g tol; updates to converge <= %d\n",
      cases, attempts, fig.input_rotated, fig.worst_free_excess / kTolerance, fig.free_better,
      fig.worst_mix_excess, fig.mix_best, fig.worst_none_gap / kTolerance,
      fig.worst_contact_depth / kTolerance, fig.max_repeats);
  EXPECT_EQ(cases, kCases);
}

/// Manual Fig. 5-11: a bar in a closed room with 0.01 of play between two walls,
/// turned about its centre until both ends dig into opposite walls: no translation
/// frees it (the other walls keep it from leaving the slot sideways).
TEST(RotationModes, Figure511BarWedgedInASlot) {
  Scene scene;
  scene.add(true, Vec3(0.6, 0.09, 0.1), Vec3::Zero());
  scene.add(false, Vec3(1.0, 0.1, 1.0), Vec3(0, 0.2, 0));   // wall y in [0.1, 0.3]
  scene.add(false, Vec3(1.0, 0.1, 1.0), Vec3(0, -0.2, 0));  // wall y in [-0.3, -0.1]
  scene.add(false, Vec3(0.1, 0.3, 1.0), Vec3(0.8, 0, 0));   // end walls at |x| >= 0.7
  scene.add(false, Vec3(0.1, 0.3, 1.0), Vec3(-0.8, 0, 0));
  scene.add(false, Vec3(1.0, 0.3, 0.1), Vec3(0, 0, 0.3));   // floor and ceiling |z| >= 0.2
  scene.add(false, Vec3(1.0, 0.3, 0.1), Vec3(0, 0, -0.3));
  // Corner (0.6, 0.09) reaches y = 0.1 at about 0.0167 rad.
  const Placement from = placementOf(Quat(Eigen::AngleAxisd(0.012, Vec3::UnitZ())), Vec3::Zero());
  ASSERT_GT(scene.distance(from.worldFromLocal()), 0.0);
  Figures fig;
  for (double angle : {0.018, 0.02, 0.025}) {
    SCOPED_TRACE(testing::Message() << "angle " << angle);
    const Placement to = placementOf(Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ())), Vec3::Zero());
    ASSERT_EQ(scene.distance(to.worldFromLocal()), 0.0);
    SceneSettings settings;
    settings.tolerance = kTolerance;
    checkModes(scene, from, to, settings, fig);
    if (HasFatalFailure()) return;
    // No translation resolves: INPUT must turn back too, and FREE needs no translation.
    EXPECT_GT(fig.input_rotated, 0);
    for (RotationMode mode : {RotationMode::Input, RotationMode::Free, RotationMode::Mix}) {
      settings.rotation_mode = mode;
      int repeats = 0;
      const DirectedResult r = converged(scene, from, to, settings, &repeats);
      EXPECT_GT(r.rpdv.z(), 0.0);
      EXPECT_NEAR(r.rpdv.z(), angle - 0.0167, 0.002);
    }
  }
  std::printf(
      "[ rotation modes ] Fig. 5-11: INPUT rotated in %d of %d; contact depth <= %.3g tol; "
      "updates <= %d\n",
      fig.input_rotated, fig.penetrating, fig.worst_contact_depth / kTolerance, fig.max_repeats);
}

}  // namespace
}  // namespace sc::test
