// SPDX-License-Identifier: MIT
// Dynamic penetration depth of convex pairs against the exact global depth from the
// hull of the Minkowski difference: a shallow penetration entered from a free pose
// just outside must find the global minimum (design.md section 4a).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "query/gjk.h"
#include "smartcollision/collision.h"
#include "support/brute_force.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

Placement placementOf(const Quat& q, const Vec3& origin) {
  Placement p;
  p.orientation = q;
  p.setOrigin(origin);
  return p;
}

TEST(ConvexPenetration, ShallowEntryFindsTheGlobalDepth) {
  const std::uint64_t seed = 20261122;
  SCOPED_TRACE(testing::Message() << "seed " << seed);
  Rng rng(seed);
  int cases = 0, exact = 0, ties = 0;
  double worst = 0.0;
  while (cases < 1000) {
    const double size = logUniform(rng, 1e-2, 1e2);
    const ConvexShape a = randomConvexShape(rng, size);
    const ConvexShape b = randomConvexShape(rng, size * uniform(rng, 0.5, 2.0));
    const Quat qa = randomRotation(rng), qb = randomRotation(rng);
    const Vec3 ob = size * Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    // Slide A from far away along -u until it touches B, then push it in a little.
    const Vec3 u = randomDirection(rng);
    double lo = 0.0, hi = 8.0 * size;  // lo: intersecting or not yet known, hi: apart
    auto depthAt = [&](double s) {
      return exactPenetrationDepth(a.poly, placementOf(qa, ob + s * u).worldFromLocal(), b.poly,
                        placementOf(qb, ob).worldFromLocal());
    };
    // GJK only locates the contact; the truth below comes from the exact hull.
    auto overlaps = [&](double s) {
      detail::SimplexCache cache;
      return detail::gjkDistance(a.poly, placementOf(qa, ob + s * u).worldFromLocal(), b.poly,
                                 placementOf(qb, ob).worldFromLocal(), {}, cache)
                 .status == detail::GjkStatus::Intersecting;
    };
    if (!overlaps(lo)) continue;  // the shapes do not overlap at equal origins: resample
    for (int i = 0; i < 50; ++i) {
      const double mid = 0.5 * (lo + hi);
      (overlaps(mid) ? lo : hi) = mid;
    }
    const double push = uniform(rng, 1e-4, 1e-2) * size;
    const Placement pen = placementOf(qa, ob + (hi - push) * u);
    const Placement pb = placementOf(qb, ob);
    const ExactDepth truth = depthAt(hi - push);
    if (!(truth.depth > 0.0) || !std::isfinite(truth.depth)) continue;
    // The free pose just outside along the exact depth direction.
    const double margin = 1e-3 * truth.depth + 1e-9 * size;
    const Placement free = placementOf(qa, pen.origin() - (truth.depth + margin) * truth.normal);

    const ModelPtr ma = convexModel(a.poly), mb = convexModel(b.poly);
    const Part part_a{ma.get(), Rigid(), 1}, part_b{mb.get(), Rigid(), 2};
    SceneSettings settings;
    settings.tolerance = 1e-3 * size;
    PairTracker tracker;
    DirectedResult out[2];
    tracker.update({&part_a, 1, free}, {&part_b, 1, pb}, {true, false}, settings, out);
    ASSERT_EQ(out[0].code, ErrorCode::Ok) << "case " << cases;
    ASSERT_GT(out[0].distance, 0.0) << "case " << cases;
    tracker.update({&part_a, 1, pen}, {&part_b, 1, pb}, {true, false}, settings, out);
    ASSERT_EQ(out[0].code, ErrorCode::Ok) << "case " << cases;
    ++cases;
    const double err = std::abs(-out[0].distance - truth.depth) / truth.depth;
    worst = std::max(worst, err);
    const bool tie = truth.runner_up - truth.depth <= 1e-6 * truth.depth;
    if (err <= 1e-6) {
      ++exact;
      if (!tie) {
        EXPECT_LE((out[0].tpdv - truth.depth * truth.normal).norm(), 1e-6 * truth.depth)
            << "case " << cases;
        EXPECT_LE((out[0].normal + truth.normal).norm(), 1e-6) << "case " << cases;
      }
      EXPECT_EQ(out[0].rpdv.norm(), 0.0);
      EXPECT_LE((out[0].contact_position - (pen.world_center - out[0].tpdv)).norm(), 1e-9 * size);
    } else if (tie) {
      ++ties;
    } else {
      ADD_FAILURE() << "case " << cases << " (" << a.kind << " vs " << b.kind << ", size "
                    << size << "): depth " << -out[0].distance << " exact " << truth.depth;
    }
  }
  RecordProperty("worst_relative_error", std::to_string(worst));
  std::printf("convex penetration: %d cases, %d exact to 1e-6, %d ties, worst rel err %.3g\n",
              cases, exact, ties, worst);
  EXPECT_GE(exact, 990);
}

}  // namespace
}  // namespace sc::test
