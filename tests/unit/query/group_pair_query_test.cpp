// SPDX-License-Identifier: MIT
// Hull-hierarchy traversal between two groups against brute force over every leaf
// pair: distance, contacts within a gap, intersection and time of impact agree;
// coherence (seeded bound, shortcuts) changes the work, never the answer.
#include "query/group_pair_query.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "support/brute_force.h"
#include "support/meshes.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

// Every pose costs one GJK per leaf pair (~101 x the elephant's patches): fewer
// poses under the sanitizers, where that is a hundred times slower.
constexpr int kDistancePoses = SC_TEST_SANITIZED ? 10 : 25;
constexpr int kToiPoses = SC_TEST_SANITIZED ? 8 : 20;
constexpr double kStopGap = 1e-3;  ///< of the time-of-impact tests

/// A soup of `count` random triangles of about `size` in a box of side `extent`.
/// A point of [-1, 1]^3, drawn last coordinate first, in sequence: the order GCC gave
/// the former Vec3(uniform, uniform, uniform), whose argument order is unspecified
/// (the tests' samples must not depend on the compiler).
Vec3 uniformInCube(test::Rng& rng) {
  const double z = test::uniform(rng, -1, 1), y = test::uniform(rng, -1, 1),
               x = test::uniform(rng, -1, 1);
  return Vec3(x, y, z);
}

MeshData randomSoup(test::Rng& rng, int count, double size, double extent) {
  MeshData soup;
  for (int t = 0; t < count; ++t) {
    const Vec3 c = 0.5 * extent * uniformInCube(rng);
    for (int k = 0; k < 3; ++k) soup.vertices.push_back(c + size * test::randomDirection(rng));
    soup.triangles.emplace_back(3 * t, 3 * t + 1, 3 * t + 2);
  }
  return soup;
}

ModelPtr modelOf(ModelKind kind, std::vector<MeshData> meshes) {
  std::vector<PiecePtr> pieces;
  for (MeshData& m : meshes) {
    Result<PiecePtr> p = buildPiece(kind, std::move(m));
    EXPECT_TRUE(p.ok()) << p.status().message();
    if (p.ok()) pieces.push_back(p.value());
  }
  return std::make_shared<const Model>(kind, std::move(pieces));
}

/// Every leaf pair by plain GJK, for reference.
struct BruteForce {
  std::vector<Leaf> t, o;

  explicit BruteForce(const GroupPairQuery& q) {
    for (int i = 0; i < q.targetLeafCount(); ++i) t.push_back(q.targetLeaf(i));
    for (int j = 0; j < q.opponentLeafCount(); ++j) o.push_back(q.opponentLeaf(j));
  }
  GjkResult pair(int i, int j, const Rigid& o_from_t) const {
    SimplexCache cache;
    return gjkDistance(*t[i].poly, o_from_t * t[i].group_from_leaf, *o[j].poly,
                       o[j].group_from_leaf, {}, cache);
  }
  double gap(int i, int j, const Rigid& o_from_t) const {
    const GjkResult r = pair(i, j, o_from_t);
    return r.status == GjkStatus::Intersecting ? 0.0 : r.distance;
  }
  /// gaps[i * o.size() + j]: every pair's gap, computed once per pose.
  std::vector<double> gaps(const Rigid& o_from_t) const {
    std::vector<double> g(t.size() * o.size());
    for (std::size_t i = 0; i < t.size(); ++i)
      for (std::size_t j = 0; j < o.size(); ++j)
        g[i * o.size() + j] = gap(static_cast<int>(i), static_cast<int>(j), o_from_t);
    return g;
  }
  double distance(const Rigid& o_from_t) const {
    const std::vector<double> g = gaps(o_from_t);
    return *std::min_element(g.begin(), g.end());
  }
  /// Conservative advancement of pair (i, j) along `delta`, up to `limit`.
  double advance(int i, int j, const Rigid& o_from_t, const Vec3& delta, double stop_gap,
                 double limit) const {
    double s = 0.0;
    for (int step = 0; step < 64 && s < limit; ++step) {
      const GjkResult r = pair(i, j, {o_from_t.rotation, o_from_t.translation + s * delta});
      if (r.status == GjkStatus::Intersecting) return s;
      // Opening from at least stop_gap / 2 at the start: its separation only grows.
      const double rate = -r.normal.dot(delta);
      if (step == 0 && r.distance >= 0.5 * stop_gap && rate <= 0.0) return limit;
      if (r.distance <= stop_gap) return s;
      // Opening, or (at the start) a gap the whole translation cannot close: no block.
      if (rate <= 0.0 || (step == 0 && r.distance - limit * delta.norm() > 0.5 * stop_gap))
        return limit;
      s = std::min(limit, s + (r.distance - 0.5 * stop_gap) / rate);
    }
    return s;
  }
  /// Conservative advancement of every pair not skipped, as documented.
  double toi(const Rigid& o_from_t, const Vec3& delta, double stop_gap,
             const std::vector<LeafPair>& skip) const {
    double limit = 1.0;
    for (int i = 0; i < static_cast<int>(t.size()); ++i) {
      for (int j = 0; j < static_cast<int>(o.size()); ++j) {
        if (!std::binary_search(skip.begin(), skip.end(), LeafPair{i, j}))
          limit = std::min(limit, advance(i, j, o_from_t, delta, stop_gap, limit));
      }
    }
    return limit;
  }
};

/// Time-of-impact cases checked, equal to all leaf pairs' advancement, and blocked.
struct ToiTally {
  int cases = 0, equal = 0, blocked = 0;
};

/// One time-of-impact case: pruned pairs are those that cannot block, so ours is
/// never more conservative than all pairs' advancement (and the same unless a pair's
/// bounding spheres pass within stop_gap / 2); at the end every pair not skipped
/// keeps stop_gap / 2.
/// The same leaf pairs (sorted by leaves: near-equal gaps from other warm starts may
/// order them apart) with gaps equal to 1e-12.
void expectSameContacts(std::vector<LeafContact> got, std::vector<LeafContact> want) {
  const auto byLeaves = [](const LeafContact& a, const LeafContact& b) {
    return LeafPair{a.t_leaf, a.o_leaf} < LeafPair{b.t_leaf, b.o_leaf};
  };
  std::sort(got.begin(), got.end(), byLeaves);
  std::sort(want.begin(), want.end(), byLeaves);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].t_leaf, want[i].t_leaf);
    ASSERT_EQ(got[i].o_leaf, want[i].o_leaf);
    EXPECT_NEAR(got[i].gap, want[i].gap, 1e-12);
  }
}

void checkToi(GroupPairQuery& q, const BruteForce& brute, const Rigid& pose, const Vec3& delta,
              double stop_gap, const std::vector<LeafPair>& skip, ToiTally& tally,
              double* toi = nullptr) {
  const double s = q.translationToi(pose, delta, stop_gap, skip);
  if (toi != nullptr) *toi = s;
  const double expected = brute.toi(pose, delta, stop_gap, skip);
  ++tally.cases;
  EXPECT_GE(s, expected - 1e-9);
  if (std::abs(s - expected) <= 1e-9) ++tally.equal;
  if (s < 1.0) ++tally.blocked;
  const Rigid end{pose.rotation, pose.translation + s * delta};
  for (int i = 0; i < q.targetLeafCount(); ++i) {
    for (int j = 0; j < q.opponentLeafCount(); ++j) {
      if (std::binary_search(skip.begin(), skip.end(), LeafPair{i, j})) continue;
      ASSERT_GE(brute.gap(i, j, end), 0.5 * stop_gap * (1 - 1e-6)) << i << " " << j;
    }
  }
}

/// All but at most one case equal to all pairs; at least `min_blocked` cases blocked
/// and some not (both outcomes occur); the counts printed.
void expectTally(const ToiTally& t, const char* what, int min_blocked) {
  EXPECT_GE(t.equal, t.cases - 1);
  EXPECT_GE(t.blocked, min_blocked);
  EXPECT_LT(t.blocked, t.cases);
  std::printf("[ group pair query ] %s: %d cases, %d equal to all pairs, %d blocked\n", what,
              t.cases, t.equal, t.blocked);
}

class GroupPairQueryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    test::Rng rng(0x6A11);
    MeshData elephant;
    ASSERT_NO_FATAL_FAILURE(elephant = test::loadTestMesh("elephant"));
    closed_ = modelOf(ModelKind::ClosedPolyhedron, {elephant});
    // Two soup pieces in one model, the second part shifted within the group.
    soup_ = modelOf(ModelKind::TriangleSoup,
                    {randomSoup(rng, 60, 0.08, 0.6), randomSoup(rng, 40, 0.05, 0.4)});
    box_ = modelOf(ModelKind::ClosedPolyhedron, {test::boxMesh(Vec3(0.05, 0.1, 0.02))});
    t_parts_[0] = Part{soup_.get(), Rigid(), 1};
    t_parts_[1] = Part{box_.get(),
                       Rigid{Mat3(Eigen::AngleAxisd(0.4, Vec3::UnitX())), Vec3(0.3, 0.0, 0.1)}, 2};
    o_parts_[0] = Part{closed_.get(), Rigid(), 3};
    target_ = GroupView{t_parts_, 2, Placement()};
    opponent_ = GroupView{o_parts_, 1, Placement()};
    query_.bind(target_, opponent_);
  }

  /// Target placed near the elephant: random rotation, centre within `spread`.
  Rigid randomPose(test::Rng& rng, double spread) const {
    const Vec3 centre = 0.5 * (closed_->bounds().min + closed_->bounds().max);
    return Rigid{test::randomRotation(rng).toRotationMatrix(),
                 centre + spread * uniformInCube(rng)};
  }

  ModelPtr closed_, soup_, box_;
  Part t_parts_[2];
  Part o_parts_[1];
  GroupView target_, opponent_;
  GroupPairQuery query_;  ///< bound to target_ and opponent_
};

TEST_F(GroupPairQueryTest, LeavesAreNumberedPieceByPiece) {
  GroupPairQuery& q = query_;
  ASSERT_EQ(q.targetLeafCount(), 60 + 40 + 1);
  EXPECT_EQ(q.opponentLeafCount(),
            static_cast<int>(closed_->pieces()[0]->internals().patches.size()));
  EXPECT_EQ(q.targetLeaf(59).piece, 0);
  EXPECT_EQ(q.targetLeaf(60).piece, 1);
  EXPECT_EQ(q.targetLeaf(99).part, 0);
  const Leaf box = q.targetLeaf(100);
  EXPECT_EQ(box.part, 1);
  EXPECT_EQ(box.poly, &box_->pieces()[0]->internals().patches[0]);
  EXPECT_VEC_NEAR(box.center, t_parts_[1].group_from_model * box.poly->center, 1e-15);
  ASSERT_EQ(q.targetLeaves().size(), 101u);
  EXPECT_EQ(q.targetLeaves()[100].poly, box.poly);
}

TEST_F(GroupPairQueryTest, DistanceContactsAndIntersectionMatchAllLeafPairs) {
  GroupPairQuery& q = query_;
  const BruteForce brute(q);
  test::Rng rng(42);
  int apart = 0, touching = 0, with_contacts = 0;
  const std::size_t o_count = brute.o.size();
  for (int c = 0; c < kDistancePoses; ++c) {
    SCOPED_TRACE(c);
    const Rigid pose = randomPose(rng, 0.8);
    const std::vector<double> gaps = brute.gaps(pose);
    const double expected = *std::min_element(gaps.begin(), gaps.end());
    LeafContact best;
    const bool found = q.distance(pose, kInfinity, best);
    ASSERT_TRUE(found);
    EXPECT_NEAR(best.gap, expected, 1e-12 * (1.0 + expected));
    EXPECT_NEAR(gaps[best.t_leaf * o_count + best.o_leaf], best.gap, 1e-12 * (1.0 + expected));
    EXPECT_EQ(q.intersects(pose), expected == 0.0);
    expected > 0.0 ? ++apart : ++touching;
    // A finite max_distance below the distance finds nothing.
    if (expected > 0.0) {
      GroupPairQuery fresh;
      fresh.bind(target_, opponent_);
      LeafContact none;
      EXPECT_FALSE(fresh.distance(pose, 0.5 * expected, none));
    }
    // Contacts within a gap: exactly the pairs brute force finds.
    const double threshold = expected + 0.05;
    std::vector<LeafContact> contacts;
    q.contacts(pose, threshold, contacts);
    std::set<std::pair<int, int>> got, want;
    for (const LeafContact& lc : contacts) got.insert({lc.t_leaf, lc.o_leaf});
    for (int i = 0; i < q.targetLeafCount(); ++i)
      for (int j = 0; j < q.opponentLeafCount(); ++j)
        if (gaps[i * o_count + j] <= threshold) want.insert({i, j});
    EXPECT_EQ(got, want);
    EXPECT_TRUE(
        std::is_sorted(contacts.begin(), contacts.end(),
                       [](const LeafContact& a, const LeafContact& b) { return a.gap < b.gap; }));
    if (!want.empty()) ++with_contacts;
  }
  std::printf("[ group pair query ] distance: %d poses apart, %d touching, %d with contacts\n",
              apart, touching, with_contacts);
  // Both kinds of pose, and contacts in about half of them (random poses).
  EXPECT_GE(apart, kDistancePoses / 4);
  EXPECT_GE(touching, kDistancePoses / 6);
  EXPECT_GE(with_contacts, kDistancePoses / 2);
}

TEST_F(GroupPairQueryTest, TranslationToiMatchesAdvancementOfAllLeafPairs) {
  GroupPairQuery& q = query_;
  const BruteForce brute(q);
  test::Rng rng(7);
  ToiTally tally;
  for (int c = 0; c < kToiPoses; ++c) {
    SCOPED_TRACE(c);
    const Rigid pose = randomPose(rng, 1.2);
    if (brute.distance(pose) == 0.0) continue;
    // Two in three towards the elephant's centre, so that many motions are blocked;
    // the third away from it, so that some are not.
    const Vec3 centre = 0.5 * (closed_->bounds().min + closed_->bounds().max);
    const double towards = c % 3 == 2 ? -1.0 : 1.0;
    const Vec3 delta = towards * test::uniform(rng, 0.3, 1.5) * (centre - pose.translation) +
                       0.2 * test::randomDirection(rng);
    // Skip the pairs within 0.02, as the proxy tracker skips its contacts.
    std::vector<LeafContact> near;
    q.contacts(pose, 0.02, near);
    std::vector<LeafPair> skip;
    for (const LeafContact& lc : near) skip.push_back({lc.t_leaf, lc.o_leaf});
    std::sort(skip.begin(), skip.end());
    ASSERT_NO_FATAL_FAILURE(checkToi(q, brute, pose, delta, kStopGap, skip, tally));
  }
  expectTally(tally, "toi", tally.cases / 4);
}

// Motions along the contact (a sideways jump near the opponent) are pruned by the
// node hulls' separating planes, which open or close at the rate n.delta: the time
// of impact stays that of every leaf pair, and the end pose stays safe.
TEST_F(GroupPairQueryTest, TranslationToiAlongTheContactMatchesAllLeafPairs) {
  GroupPairQuery& q = query_;
  const BruteForce brute(q);
  test::Rng rng(19);
  ToiTally tally;
  for (int c = 0; tally.cases < kToiPoses && c < 20 * kToiPoses; ++c) {
    SCOPED_TRACE(c);
    const Rigid pose = randomPose(rng, 1.2);
    LeafContact closest;
    if (!q.distance(pose, kInfinity, closest) || closest.intersecting) continue;
    if (closest.gap < 2.0 * kStopGap || closest.gap > 0.1) continue;  // near the opponent
    // Orthogonal to the closest pair's normal, with a little of it either way.
    const Vec3 side = closest.normal.unitOrthogonal();
    const Vec3 along = Eigen::AngleAxisd(test::uniform(rng, 0, 2 * M_PI), closest.normal) * side;
    const Vec3 delta =
        test::uniform(rng, 0.05, 0.6) * along + test::uniform(rng, -0.02, 0.02) * closest.normal;
    ASSERT_NO_FATAL_FAILURE(checkToi(q, brute, pose, delta, kStopGap, {}, tally));
  }
  EXPECT_EQ(tally.cases, kToiPoses);
  expectTally(tally, "sideways toi", 1);  // some sideways motions meet the opponent
}

// A slide's sweeps: three in a row at one rotation, each from where the last stopped,
// the first towards the elephant, the others in new directions. The separating planes
// one sweep finds serve the next (PlaneMemo): each still equals all leaf pairs'
// advancement. Halfway the opponent moves within its group towards the target and the
// last slide's first sweep runs again: planes kept from before must not serve.
TEST_F(GroupPairQueryTest, SweepsInARowAtOneRotationMatchAllLeafPairs) {
  test::Rng rng(23);
  const Vec3 centre = 0.5 * (closed_->bounds().min + closed_->bounds().max);
  constexpr int kSlides = SC_TEST_SANITIZED ? 4 : 24;
  ToiTally tally;
  Rigid pose, last;  // last: the start of the last slide run
  for (int c = 0; c < kSlides; ++c) {
    SCOPED_TRACE(c);
    if (c == kSlides / 2) {  // the elephant comes a tenth of the way to meet the target
      o_parts_[0].group_from_model.translation = 0.1 * (last.translation - centre);
      query_.bind(target_, opponent_);
      pose = last;
    } else {
      pose = randomPose(rng, 1.2);
    }
    const BruteForce brute(query_);
    if (brute.distance(pose) == 0.0) continue;
    last = pose;
    Rigid at = pose;
    for (int k = 0; k < 3; ++k) {
      const Vec3 delta = k == 0 ? Vec3(0.9 * (centre - at.translation))
                                : Vec3(test::uniform(rng, 0.05, 0.5) * test::randomDirection(rng));
      std::vector<LeafContact> near;  // skipped, as the proxy tracker skips its contacts
      query_.contacts(at, 0.02, near);
      std::vector<LeafPair> skip;
      for (const LeafContact& lc : near) skip.push_back({lc.t_leaf, lc.o_leaf});
      std::sort(skip.begin(), skip.end());
      double s = 0.0;
      ASSERT_NO_FATAL_FAILURE(checkToi(query_, brute, at, delta, kStopGap, skip, tally, &s));
      at.translation += s * delta;
    }
  }
  expectTally(tally, "sweeps in a row", tally.cases / 4);
}

// A long move's end is measured first (a fresh tracker's work), its traversal keeping
// its separating planes at the end's rotation (distance's sweep_next): the sweep from
// the start then relies on them and still stops where every leaf pair does.
TEST_F(GroupPairQueryTest, SweepAfterTheEndsDistanceKeptItsPlanesMatchesAllLeafPairs) {
  test::Rng rng(29);
  const BruteForce brute(query_);
  const Vec3 centre = 0.5 * (closed_->bounds().min + closed_->bounds().max);
  ToiTally tally;
  for (int c = 0; c < kToiPoses; ++c) {
    SCOPED_TRACE(c);
    const Rigid start = randomPose(rng, 1.2);
    if (brute.distance(start) == 0.0) continue;
    // Past the elephant's centre, or sideways: many ends free, many paths blocked.
    const Vec3 to_centre = centre - start.translation;
    const Vec3 delta =
        c % 2 == 0
            ? Vec3(test::uniform(rng, 0.5, 2.0) * to_centre + 0.3 * test::randomDirection(rng))
            : Vec3(0.8 * to_centre.norm() *
                   to_centre.cross(test::randomDirection(rng)).normalized());
    LeafContact end;
    query_.distance({start.rotation, start.translation + delta}, kInfinity, end, true);
    ASSERT_NO_FATAL_FAILURE(checkToi(query_, brute, start, delta, kStopGap, {}, tally));
  }
  expectTally(tally, "sweeps after the end's distance", tally.cases / 4);
}

TEST_F(GroupPairQueryTest, CoherenceSavesWorkButNotAccuracy) {
  GroupPairQuery warm;
  warm.bind(target_, opponent_);
  const BruteForce brute(warm);
  test::Rng rng(99);
  Rigid pose = randomPose(rng, 0.7);
  const Vec3 step = 2e-3 * test::randomDirection(rng);
  const Mat3 turn = Eigen::AngleAxisd(2e-3, test::randomDirection(rng)).toRotationMatrix();
  long warm_gjk = 0, cold_gjk = 0;
  int shortcuts = 0;
  for (int k = 0; k < 60; ++k) {
    pose = Rigid{turn * pose.rotation, pose.translation + step};
    LeafContact w, c;
    const bool found_w = warm.distance(pose, kInfinity, w);
    warm_gjk += warm.counters().node_gjk + warm.counters().leaf_gjk;
    GroupPairQuery cold;
    cold.bind(target_, opponent_);
    const bool found_c = cold.distance(pose, kInfinity, c);
    cold_gjk += cold.counters().node_gjk + cold.counters().leaf_gjk;
    ASSERT_TRUE(found_w && found_c);
    EXPECT_NEAR(w.gap, c.gap, 1e-12 * (1.0 + c.gap));
    if (k % 10 == 0) {
      EXPECT_NEAR(w.gap, brute.distance(pose), 1e-12 * (1.0 + c.gap));
    }
    // Right after distance(): contacts just below it are empty without traversal.
    if (w.gap > 0.0) {
      std::vector<LeafContact> out;
      warm.contacts(pose, 0.5 * w.gap, out);
      EXPECT_TRUE(out.empty());
      shortcuts += warm.counters().shortcut ? 1 : 0;
      EXPECT_FALSE(warm.intersects(pose));
    }
  }
  std::printf("[ group pair query ] 60 coherent steps: GJK runs warm %ld, cold %ld; %d shortcuts\n",
              warm_gjk, cold_gjk, shortcuts);
  EXPECT_LT(warm_gjk, cold_gjk);
  EXPECT_GT(shortcuts, 0);
}

TEST_F(GroupPairQueryTest, MovingAPartWithinItsGroupForgetsTheKnownDistance) {
  GroupPairQuery& q = query_;
  test::Rng rng(5);
  Rigid pose;
  LeafContact best;
  do {
    pose = randomPose(rng, 1.0);
  } while (!q.distance(pose, kInfinity, best) || best.gap < 0.05);
  // Move the box part right onto the elephant's closest point: the shortcut must
  // not answer from the old distance.
  const Leaf box = q.targetLeaf(100);
  const Vec3 goal = pose.inverse() * best.point_o;  // in the target group frame
  t_parts_[1].group_from_model.translation += goal - box.center;
  q.bind(target_, opponent_);
  EXPECT_TRUE(q.intersects(pose));
  EXPECT_FALSE(q.counters().shortcut);
}

TEST_F(GroupPairQueryTest, ContactsNearAndItsTimeOfImpactEqualTraversalsAlongASlide) {
  GroupPairQuery near, plain;
  near.bind(target_, opponent_);
  plain.bind(target_, opponent_);
  test::Rng rng(31), delta_rng(32);
  const double threshold = 0.01, margin = 0.01;
  int reused = 0, steps = 0, with_contacts = 0, toi_from_pairs = 0, toi_blocked = 0;
  int ahead = 0;  // calls that installed pairs gathered ahead of need, over several calls
  for (int run = 0; run < 6; ++run) {
    Rigid pose = randomPose(rng, 0.6);
    for (int k = 0; k < 30; ++k, ++steps) {
      SCOPED_TRACE(k);
      // Small steps at one rotation, now and then a jump beyond the margin or a turn.
      pose.translation += (k % 10 == 9 ? 0.02 : 0.003) * test::randomDirection(rng);
      if (k == 15) pose.rotation = test::randomRotation(rng).toRotationMatrix() * pose.rotation;
      std::vector<LeafContact> got, want;
      near.contactsNear(pose, threshold, margin, got);
      const bool traversed = near.counters().node_pairs > 0 || near.counters().shortcut;
      if (near.counters().ahead_installed) ++ahead;
      plain.contacts(pose, threshold, want);
      ASSERT_NO_FATAL_FAILURE(expectSameContacts(got, want));
      if (!traversed) ++reused;
      if (!want.empty()) ++with_contacts;
      // A short translation's time of impact from the kept pairs equals the
      // traversal's, the closest contacts skipped as a slide skips them.
      std::vector<LeafPair> skip;
      for (const LeafContact& c : want)
        if (c.gap <= 0.0005) skip.push_back({c.t_leaf, c.o_leaf});
      std::sort(skip.begin(), skip.end());
      const Vec3 centre = 0.5 * (closed_->bounds().min + closed_->bounds().max);
      const Vec3 delta = 0.008 * ((centre - pose.translation).normalized() +
                                  0.5 * test::randomDirection(delta_rng));
      const double s_near = near.translationToi(pose, delta, 0.002, skip);
      const bool toi_reused = near.counters().node_pairs == 0 && !near.counters().shortcut;
      const double s_plain = plain.translationToi(pose, delta, 0.002, skip);
      EXPECT_NEAR(s_near, s_plain, 1e-9);
      if (toi_reused) ++toi_from_pairs;
      if (s_plain < 1.0) ++toi_blocked;
    }
  }
  EXPECT_GT(toi_from_pairs, steps / 3);
  EXPECT_GT(toi_blocked, steps / 10);
  // Most steps reuse the pairs, and the comparison saw contacts.
  EXPECT_GT(reused, steps / 3);
  EXPECT_GT(with_contacts, steps / 4);
  EXPECT_GT(ahead, steps / 20);
  std::printf(
      "[ group pair query ] contactsNear: %d of %d steps reused, %d with contacts, %d "
      "rebuilt ahead; time of impact from the pairs %d times, %d blocked\n",
      reused, steps, with_contacts, ahead, toi_from_pairs, toi_blocked);
}

// Long slow slides, each rebuild of the near pairs started from the last one's front
// (near_front.h) as long as it serves: at every call the pairs are those of a full
// traversal from the roots, leaf for leaf.
TEST_F(GroupPairQueryTest, ContactsNearRebuiltFromTheFrontEqualTraversalsFromTheRoots) {
  GroupPairQuery near, plain;
  near.bind(target_, opponent_);
  plain.bind(target_, opponent_);
  test::Rng rng(53);
  const double threshold = 0.01, margin = 0.02;
  const Mat3 turn = Eigen::AngleAxisd(0.003, Vec3(-0.4, 0.2, 1.0).normalized()).toRotationMatrix();
  int steps = 0, with_contacts = 0;
  for (int run = 0; run < (SC_TEST_SANITIZED ? 2 : 5); ++run) {
    Rigid pose = randomPose(rng, 0.5);
    const Vec3 drift = 0.004 * test::randomDirection(rng);
    for (int k = 0; k < 80; ++k, ++steps) {
      SCOPED_TRACE(k);
      pose.translation += drift + 0.002 * test::randomDirection(rng);
      pose.rotation = turn * pose.rotation;
      std::vector<LeafContact> got, want;
      near.contactsNear(pose, threshold, margin, got);
      plain.contacts(pose, threshold, want);
      ASSERT_NO_FATAL_FAILURE(expectSameContacts(got, want));
      if (!want.empty()) ++with_contacts;
    }
  }
  EXPECT_GT(with_contacts, steps / 4);
  EXPECT_GT(near.frontRebuilds(), steps / 10);
  std::printf("[ group pair query ] %d steps, %d with contacts, %d rebuilds from the front\n",
              steps, with_contacts, near.frontRebuilds());
}

// A rebuild takes the leaf pairs the query already keeps with their bounds (last gap
// less the motion since), unmeasured: along slow, turning slides the answers are those
// of a query measuring every pair and of a full traversal, pair for pair, with fewer
// leaf GJK runs.
TEST_F(GroupPairQueryTest, ContactsNearTakingKeptPairsInRebuildsEqualsMeasuringThem) {
  GroupPairQuery reuse, measure, plain;
  reuse.bind(target_, opponent_);
  measure.bind(target_, opponent_);
  measure.setNearReuseInRebuilds(false);
  plain.bind(target_, opponent_);
  test::Rng rng(71);
  const double threshold = 0.01, margin = 0.02;
  const Mat3 turn = Eigen::AngleAxisd(0.004, Vec3(0.5, -0.3, 1.0).normalized()).toRotationMatrix();
  int steps = 0, with_contacts = 0;
  long gjk_reuse = 0, gjk_measure = 0;
  const auto leafGjk = [](const GroupPairQuery& q) {
    return q.counters().leaf_gjk + q.counters().ahead_gjk;
  };
  for (int run = 0; run < (SC_TEST_SANITIZED ? 2 : 5); ++run) {
    Rigid pose = randomPose(rng, 0.5);
    const Vec3 drift = 0.003 * test::randomDirection(rng);
    for (int k = 0; k < 80; ++k, ++steps) {
      SCOPED_TRACE(k);
      pose.translation += drift + 0.002 * test::randomDirection(rng);
      pose.rotation = turn * pose.rotation;
      std::vector<LeafContact> got, measured, want;
      reuse.contactsNear(pose, threshold, margin, got);
      measure.contactsNear(pose, threshold, margin, measured);
      plain.contacts(pose, threshold, want);
      ASSERT_NO_FATAL_FAILURE(expectSameContacts(got, measured));
      ASSERT_NO_FATAL_FAILURE(expectSameContacts(got, want));
      for (const LeafContact& c : got) EXPECT_TRUE(c.measured);
      gjk_reuse += leafGjk(reuse);
      gjk_measure += leafGjk(measure);
      if (!want.empty()) ++with_contacts;
    }
  }
  EXPECT_GT(with_contacts, steps / 4);
  EXPECT_LT(gjk_reuse, gjk_measure);
  std::printf(
      "[ group pair query ] %d steps, %d with contacts; GJK runs %ld taking kept pairs, "
      "%ld measuring them\n",
      steps, with_contacts, gjk_reuse, gjk_measure);
}

// Slides broken by moves of one to six times the rebuild's reach (a proxy's slide
// iterations after a jump): a rebuild starts from the last front, its bounds lowered
// by the motion and raised again by the node spheres at the new pose, or from what a
// rebuild given up on the way left; the pairs are a full traversal's throughout.
TEST_F(GroupPairQueryTest, ContactsNearAfterLongMovesEqualTraversalsFromTheRoots) {
  GroupPairQuery near, plain;
  near.bind(target_, opponent_);
  plain.bind(target_, opponent_);
  test::Rng rng(67);
  const double threshold = 0.01, margin = 0.02, reach = threshold + margin;
  int steps = 0, with_contacts = 0, long_moves = 0, served_after_long_moves = 0;
  for (int run = 0; run < (SC_TEST_SANITIZED ? 2 : 5); ++run) {
    Rigid pose = randomPose(rng, 0.5);
    for (int k = 0; k < 60; ++k, ++steps) {
      SCOPED_TRACE(k);
      const bool long_move = k % 4 == 3;
      const double length = long_move ? test::uniform(rng, reach, 6.0 * reach) : 0.003;
      pose.translation += length * test::randomDirection(rng);
      const int served = near.frontRebuilds();
      std::vector<LeafContact> got, want;
      near.contactsNear(pose, threshold, margin, got);
      plain.contacts(pose, threshold, want);
      ASSERT_NO_FATAL_FAILURE(expectSameContacts(got, want));
      if (!want.empty()) ++with_contacts;
      long_moves += long_move;
      served_after_long_moves += long_move && near.frontRebuilds() > served;
    }
  }
  EXPECT_GT(with_contacts, steps / 4);
  EXPECT_GT(served_after_long_moves, long_moves / 4);
  std::printf(
      "[ group pair query ] %d steps, %d with contacts, %d of %d long moves rebuilt "
      "from a front\n",
      steps, with_contacts, served_after_long_moves, long_moves);
}

// One call with a far larger threshold (a long advancement) gathers a large set;
// the calls after it, with a small threshold, rebuild it at their own reach instead of
// scanning it on every call, and answer as full traversals throughout.
TEST_F(GroupPairQueryTest, ContactsNearGivesUpASetGatheredForAFarLargerReach) {
  GroupPairQuery near, plain;
  near.bind(target_, opponent_);
  plain.bind(target_, opponent_);
  test::Rng rng(61);
  const double threshold = 0.002, margin = 0.004, large = 0.1;
  int replaced = 0, runs = 0;
  for (int run = 0; run < (SC_TEST_SANITIZED ? 2 : 5); ++run, ++runs) {
    Rigid pose = randomPose(rng, 0.5);
    std::vector<LeafContact> got, want;
    near.contactsNear(pose, large, margin, got);
    const Vec3 drift = 0.0005 * test::randomDirection(rng);
    for (int k = 0; k < 40; ++k) {
      SCOPED_TRACE(k);
      pose.translation += drift;
      near.contactsNear(pose, threshold, margin, got);
      plain.contacts(pose, threshold, want);
      ASSERT_EQ(got.size(), want.size());
    }
    // Kept at the large reach, the set would still cover 0.08 here.
    if (near.nearCoveredReach(pose) <= 4.0 * (threshold + margin)) ++replaced;
  }
  EXPECT_EQ(replaced, runs);
}

// A proxy just out of contact: distance() answers from the pairs contactsNear()
// keeps when they cover the pose, and equals a fresh query's distance, in contact or
// not, covered or not.
TEST_F(GroupPairQueryTest, DistanceFromTheNearPairsEqualsAFreshQuery) {
  GroupPairQuery near;
  near.bind(target_, opponent_);
  test::Rng rng(59);
  const double threshold = 0.01, margin = 0.02;
  int steps = 0, from_pairs = 0, apart = 0, apart_from_pairs = 0;
  for (int run = 0; run < (SC_TEST_SANITIZED ? 2 : 6); ++run) {
    Rigid pose = randomPose(rng, 0.5);
    const Vec3 drift = 0.003 * test::randomDirection(rng);
    for (int k = 0; k < 40; ++k, ++steps) {
      SCOPED_TRACE(k);
      pose.translation += drift;
      std::vector<LeafContact> contacts;
      near.contactsNear(pose, threshold, margin, contacts);
      const Rigid moved{pose.rotation, pose.translation + 0.002 * test::randomDirection(rng)};
      GroupPairQuery fresh;
      fresh.bind(target_, opponent_);
      LeafContact got, want;
      const bool found = near.distance(moved, kInfinity, got);
      ASSERT_EQ(found, fresh.distance(moved, kInfinity, want));
      EXPECT_NEAR(got.gap, want.gap, 1e-12 * (1.0 + want.gap));
      EXPECT_EQ(got.intersecting, want.intersecting);
      const bool untraversed = near.counters().node_pairs == 0 && near.counters().leaf_gjk > 0;
      from_pairs += untraversed;
      apart += !want.intersecting;
      apart_from_pairs += untraversed && !want.intersecting;
    }
  }
  EXPECT_GT(from_pairs, steps / 10);
  EXPECT_GT(apart_from_pairs, 5);
  std::printf(
      "[ group pair query ] %d distances, %d from the near pairs; %d apart, %d of them "
      "from the near pairs\n",
      steps, from_pairs, apart, apart_from_pairs);
}

// Warm state after jumps of every size (beyond the kept pairs' reach, up to a
// teleport): the carried query answers what a fresh one answers at that pose, for
// the distance, the contacts near and a time of impact, and the kept pairs it no
// longer covers are rebuilt, not followed.
TEST_F(GroupPairQueryTest, AfterAJumpTheCarriedQueryAnswersAsAFreshOne) {
  GroupPairQuery warm;
  warm.bind(target_, opponent_);
  test::Rng rng(53);
  const double threshold = 0.01, margin = 0.01;
  int jumps = 0, with_contacts = 0;
  for (int run = 0; run < (SC_TEST_SANITIZED ? 2 : 5); ++run) {
    Rigid pose = randomPose(rng, 0.6);
    for (int k = 0; k < 24; ++k) {
      SCOPED_TRACE(k);
      const bool jump = k % 6 == 5;
      const double length = jump ? std::array<double, 3>{0.05, 0.2, 1.0}[k / 6 % 3] : 0.002;
      pose.translation += length * test::randomDirection(rng);
      if (jump) pose.rotation = test::randomRotation(rng).toRotationMatrix() * pose.rotation;
      GroupPairQuery fresh;
      fresh.bind(target_, opponent_);
      LeafContact w, f;
      const bool w_found = warm.distance(pose, kInfinity, w);
      ASSERT_EQ(w_found, fresh.distance(pose, kInfinity, f));
      EXPECT_NEAR(w.gap, f.gap, 1e-12);
      std::vector<LeafContact> got, want;
      warm.contactsNear(pose, threshold, margin, got);
      fresh.contacts(pose, threshold, want);
      std::set<std::pair<int, int>> got_pairs, want_pairs;
      for (const LeafContact& c : got) got_pairs.insert({c.t_leaf, c.o_leaf});
      for (const LeafContact& c : want) want_pairs.insert({c.t_leaf, c.o_leaf});
      EXPECT_EQ(got_pairs, want_pairs);
      const Vec3 delta = 0.05 * test::randomDirection(rng);
      EXPECT_NEAR(warm.translationToi(pose, delta, 0.002, {}),
                  fresh.translationToi(pose, delta, 0.002, {}), 1e-9);
      jumps += jump;
      with_contacts += !want.empty();
    }
  }
  EXPECT_GT(with_contacts, 10);
  std::printf("[ group pair query ] after %d jumps: warm equals fresh; %d poses with contacts\n",
              jumps, with_contacts);
}

// Two elephants apart, the target orbiting the other and jumping sideways by 1 to 4 %
// of the size now and then: after a jump the carried query's last closest pair, its
// seed, is refined on its real triangles (a virtual feature of its patch hull) no
// more than a fresh query refines it, which measures it only if the traversal's bound
// lets it; the distances equal a fresh query's.
TEST_F(GroupPairQueryTest, AfterAJumpTheSeedIsRefinedOnlyAsAFreshQueryWould) {
  Part target_part{closed_.get(), Rigid(), 7};
  const GroupView target{&target_part, 1, Placement()};
  GroupPairQuery warm;
  warm.bind(target, opponent_);
  const Vec3 centre = 0.5 * (closed_->bounds().min + closed_->bounds().max);
  const double size = (closed_->bounds().max - closed_->bounds().min).norm();
  // Offset along u (from the centre) where the target, turned by q, is `gap` apart.
  auto placed = [&](const Mat3& q, const Vec3& u, double gap) {
    double s = size;
    for (int k = 0; k < 60; ++k) {
      GroupPairQuery fresh;
      fresh.bind(target, opponent_);
      LeafContact c;
      fresh.distance({q, centre + s * u - q * centre}, kInfinity, c);
      if (c.intersecting) {
        s += 0.05 * size;
        continue;
      }
      if (std::abs(c.gap - gap) < 0.05 * gap) break;
      s -= c.gap - gap;
    }
    return Rigid{q, centre + s * u - q * centre};
  };
  test::Rng rng(71);
  int jumps = 0, refined_fresh = 0, refined_warm = 0;
  for (int run = 0; run < (SC_TEST_SANITIZED ? 4 : 16); ++run) {
    const Mat3 q = test::randomRotation(rng).toRotationMatrix();
    Vec3 u = test::randomDirection(rng);
    const Vec3 axis = u.cross(test::randomDirection(rng)).normalized();
    for (int k = 0; k < 6; ++k) {
      SCOPED_TRACE(k);
      const bool jump = k % 3 == 2;
      u = Eigen::AngleAxisd(jump ? 0.01 * (1 + run % 4) : 0.002, axis) * u;
      const Rigid pose = placed(q, u, 0.01 * size);
      GroupPairQuery fresh;
      fresh.bind(target, opponent_);
      LeafContact w, f;
      ASSERT_EQ(warm.distance(pose, kInfinity, w), fresh.distance(pose, kInfinity, f));
      EXPECT_NEAR(w.gap, f.gap, 1e-12);
      if (!jump) continue;
      ++jumps;
      refined_warm += warm.counters().refined;
      refined_fresh += fresh.counters().refined;
      EXPECT_LE(warm.counters().refined, fresh.counters().refined);
    }
  }
  std::printf(
      "[ group pair query ] %d jumps between elephants: leaf pairs refined %d carried, "
      "%d fresh\n",
      jumps, refined_warm, refined_fresh);
}

// A leaf pair whose hulls are closest on a virtual feature is measured on its real
// triangles only when no pair is nearer than its hulls: refined pairs never number
// more than the leaf pairs whose hulls are nearer than the answer (a fresh query that
// met such a pair first used to refine it against no bound at all).
TEST_F(GroupPairQueryTest, DistanceRefinesOnlyPairsWhoseHullsAreWithinTheAnswer) {
  Part target_part{closed_.get(), Rigid(), 7};
  const GroupView target{&target_part, 1, Placement()};
  GroupPairQuery probe;
  probe.bind(target, opponent_);
  const BruteForce brute(probe);
  const Vec3 centre = 0.5 * (closed_->bounds().min + closed_->bounds().max);
  const double size = (closed_->bounds().max - closed_->bounds().min).norm();
  test::Rng rng(71);
  int poses = 0, refined = 0;
  for (int c = 0; c < (SC_TEST_SANITIZED ? 4 : 16); ++c) {
    SCOPED_TRACE(c);
    // A turned elephant beside the other, a few hundredths of its size apart.
    const Mat3 q = test::randomRotation(rng).toRotationMatrix();
    const Vec3 u = test::randomDirection(rng);
    Rigid pose{q, centre - q * centre};
    for (double s = 0.3 * size; s < 2.0 * size; s += 0.02 * size) {
      pose.translation = centre + s * u - q * centre;
      if (!probe.intersects(pose)) break;
    }
    GroupPairQuery fresh;
    fresh.bind(target, opponent_);
    LeafContact best;
    ASSERT_TRUE(fresh.distance(pose, kInfinity, best));
    const std::vector<double> gaps = brute.gaps(pose);
    // Hulls strictly nearer than the answer: the pairs that had to be refined.
    const long within = std::count_if(gaps.begin(), gaps.end(), [&](double g) {
      return g < best.gap - 1e-12 * (1.0 + best.gap);
    });
    EXPECT_LE(fresh.counters().refined, within);
    refined += fresh.counters().refined;
    ++poses;
  }
  std::printf("[ group pair query ] %d fresh distances beside an elephant: %d pairs refined\n",
              poses, refined);
}

// A drifting, slowly turning target (a body pushed along a surface): the kept pairs
// give the traversal's contacts, and once a pair was measured, only its own motion
// since brings it back, so a second, near-identical pose re-measures only the pairs
// within the threshold, however far the group drifted since the pairs were gathered.
TEST_F(GroupPairQueryTest, ContactsNearMeasuresAgainOnlyPairsNearTheThreshold) {
  GroupPairQuery near, plain;
  near.bind(target_, opponent_);
  plain.bind(target_, opponent_);
  test::Rng rng(41);
  const double threshold = 0.01, margin = 0.02;
  const Mat3 turn = Eigen::AngleAxisd(0.002, Vec3(0.3, 1.0, -0.2).normalized()).toRotationMatrix();
  int checked = 0, cheap = 0;
  // Random walks until a few checks saw pairs in contact and more than ten checks ran
  // (at most 40 walks).
  for (int run = 0; run < 40 && (cheap < 4 || checked <= 10); ++run) {
    Rigid pose = randomPose(rng, 0.6);
    const Vec3 drift = 0.0015 * test::randomDirection(rng);
    for (int k = 0; k < 12; ++k) {
      SCOPED_TRACE(k);
      pose.translation += drift;
      pose.rotation = turn * pose.rotation;
      std::vector<LeafContact> got, again, want;
      near.contactsNear(pose, threshold, margin, got);
      plain.contacts(pose, threshold, want);
      ASSERT_EQ(got.size(), want.size());
      // A nudge a thousand times smaller than a step.
      const Rigid nudged{pose.rotation, pose.translation + 1e-6 * Vec3(1, -1, 1)};
      near.contactsNear(nudged, threshold, margin, again);
      // Rebuilt, or pairs gathered ahead just installed: not this check.
      if (near.counters().node_pairs > 0 || near.counters().ahead_installed || k == 0) continue;
      std::vector<LeafContact> close;
      plain.contacts(nudged, threshold + 1e-5, close);
      EXPECT_LE(near.counters().leaf_gjk, static_cast<int>(close.size()));
      ++checked;
      if (!close.empty()) ++cheap;
    }
  }
  EXPECT_GT(checked, 10);
  EXPECT_GE(cheap, 4);  // the check saw pairs in contact
}

/// An n x n grid of `cell`-sized squares about the origin, two triangles each, at
/// the heights z = bump * sin(40 x) cos(30 y).
MeshData gridSoup(int n, double cell, double bump) {
  MeshData grid;
  const double o = -0.5 * n * cell;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const double x = o + i * cell, y = o + j * cell;
      grid.vertices.emplace_back(x, y, bump * std::sin(40.0 * x) * std::cos(30.0 * y));
    }
  }
  const auto at = [n](int i, int j) { return i * (n + 1) + j; };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      grid.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      grid.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return grid;
}

// A plate landing on a bumpy floor, then sliding along it, about a twelfth of the
// margin per call: the pairs found grow from none to thousands as the plate lands, far
// more than the last rebuild's work predicts. A rebuild run ahead is paced by the
// motion, and when it is due unfinished, it runs only as far as the pose needs: no
// call does half a rebuild's work (one did 61% of one when due rebuilds ran to their
// end at a pace set by the last rebuild alone).
/// Inner nodes of the model's pieces that keep no hull.
int hullLessNodes(const Model& model) {
  int count = 0;
  for (const PiecePtr& piece : model.pieces())
    for (const HullBvhNode& n : piece->internals().hierarchy.nodes)
      count += !n.leaf() && !n.hasPolytope() ? 1 : 0;
  return count;
}

// A soup's hierarchy, in which some inner nodes keep no hull (odd depths, nodes of
// few points; their spheres bound them), answers as every leaf pair does against a
// closed mesh and a soup: distance, contacts within a gap and intersection; soup
// against soup as every triangle pair.
TEST(GroupPairQueryHullLess, DistancesEqualBruteForceOnASoupAndAClosedMesh) {
  MeshData elephant;
  ASSERT_NO_FATAL_FAILURE(elephant = test::loadTestMesh("elephant"));
  const MeshData torus = test::torusMesh(0.25, 0.08, 24, 12);
  const ModelPtr closed = modelOf(ModelKind::ClosedPolyhedron, {elephant});
  const ModelPtr soup = modelOf(ModelKind::TriangleSoup, {torus});
  const ModelPtr ring = modelOf(ModelKind::ClosedPolyhedron, {torus});
  ASSERT_TRUE(closed && soup && ring);
  EXPECT_GT(hullLessNodes(*soup), 100);
  const std::pair<const Model*, const Model*> pairs[] = {
      {soup.get(), closed.get()}, {ring.get(), soup.get()}, {soup.get(), soup.get()}};
  test::Rng rng(0x41F);
  int touching = 0, apart = 0;
  for (const auto& [target, opponent] : pairs) {
    const Part t_part{target, Rigid(), 1}, o_part{opponent, Rigid(), 2};
    const GroupView t_view{&t_part, 1, Placement()}, o_view{&o_part, 1, Placement()};
    GroupPairQuery q;
    q.bind(t_view, o_view);
    const BruteForce brute(q);
    const Vec3 centre = 0.5 * (opponent->bounds().min + opponent->bounds().max);
    for (int c = 0; c < kDistancePoses; ++c) {
      SCOPED_TRACE(c);
      const Rigid pose{test::randomRotation(rng).toRotationMatrix(),
                       centre + 0.5 * uniformInCube(rng)};
      const std::vector<double> gaps = brute.gaps(pose);
      const double expected = *std::min_element(gaps.begin(), gaps.end());
      LeafContact best;
      ASSERT_TRUE(q.distance(pose, kInfinity, best));
      EXPECT_NEAR(best.gap, expected, 1e-12 * (1.0 + expected));
      EXPECT_EQ(q.intersects(pose), expected == 0.0);
      if (target == opponent) {  // soup against soup: every triangle pair
        const double surface = test::meshSurfaceDistance(torus, pose, torus, Rigid()).distance;
        EXPECT_NEAR(best.gap, surface, 1e-12 * (1.0 + surface));
      }
      const double threshold = expected + 0.02;
      std::vector<LeafContact> contacts;
      q.contacts(pose, threshold, contacts);
      std::set<std::pair<int, int>> got, want;
      for (const LeafContact& lc : contacts) got.insert({lc.t_leaf, lc.o_leaf});
      for (std::size_t i = 0; i < brute.t.size(); ++i)
        for (std::size_t j = 0; j < brute.o.size(); ++j)
          if (gaps[i * brute.o.size() + j] <= threshold)
            want.insert({static_cast<int>(i), static_cast<int>(j)});
      EXPECT_EQ(got, want);
      expected > 0.0 ? ++apart : ++touching;
    }
  }
  EXPECT_GE(apart, kDistancePoses / 2);
  EXPECT_GE(touching, kDistancePoses / 2);
}

TEST(GroupPairQueryPacing, ALandingPlateSpreadsItsRebuildsOverTheCalls) {
  const ModelPtr floor = modelOf(ModelKind::TriangleSoup, {gridSoup(40, 0.025, 0.006)});
  const ModelPtr plate = modelOf(ModelKind::TriangleSoup, {gridSoup(16, 0.025, 0.0)});
  const Part t_part{plate.get(), Rigid(), 1}, o_part{floor.get(), Rigid(), 2};
  const GroupView target{&t_part, 1, Placement()}, opponent{&o_part, 1, Placement()};
  GroupPairQuery near, plain;
  near.bind(target, opponent);
  plain.bind(target, opponent);
  const double threshold = 0.004, margin = 0.008;
  const Vec3 drop(0.0, 0.0, -0.0007), slide(0.0005, 0.0004, 0.0);
  Rigid pose{Mat3::Identity(), Vec3(0.0, 0.0, 0.03)};
  int most = 0, largest_rebuild = 0, calls = 0;
  std::vector<LeafContact> got, want;
  for (; calls < 90; ++calls) {
    SCOPED_TRACE(calls);
    pose.translation += pose.translation.z() > 0.0085 ? drop : slide;
    near.contactsNear(pose, threshold, margin, got);
    most = std::max(most, near.counters().node_pairs + near.counters().ahead_node_pairs);
    plain.contacts(pose, threshold, want);
    ASSERT_EQ(got.size(), want.size());
    plain.contacts(pose, threshold + margin, want);  // what a rebuild here takes
    largest_rebuild = std::max(largest_rebuild, plain.counters().node_pairs);
  }
  EXPECT_GT(want.size(), 1000u);  // the plate did land on the floor
  EXPECT_LT(most, largest_rebuild / 2);
  std::printf(
      "[ group pair query ] landing plate: most node pairs in a call %d, largest "
      "rebuild %d, %zu pairs within the reach at the end\n",
      most, largest_rebuild, want.size());
}

// Two overlapping soups of 200 triangles: 40,000 leaf pairs within the threshold,
// more than kMaxContacts. Both queries keep kMaxContacts pairs, sorted (memory
// bounded; two overlapping 10k-triangle meshes would hold 10^8), and contactsNear
// says how far its answer is complete: every pair within that reach is kept.
TEST(GroupPairQueryCap, ContactsAreCappedAndCompleteUpToTheReachTheyCover) {
  test::Rng rng(0xCA9);
  const ModelPtr a = modelOf(ModelKind::TriangleSoup, {randomSoup(rng, 200, 0.05, 0.3)});
  const ModelPtr b = modelOf(ModelKind::TriangleSoup, {randomSoup(rng, 200, 0.05, 0.3)});
  Part ta{a.get(), Rigid(), 1}, ob{b.get(), Rigid(), 2};
  GroupPairQuery q;
  q.bind(GroupView{&ta, 1, Placement()}, GroupView{&ob, 1, Placement()});
  const std::size_t cap = GroupPairQuery::kMaxContacts;
  ASSERT_GT(std::size_t(q.targetLeafCount()) * std::size_t(q.opponentLeafCount()), cap);
  const Rigid pose;
  const std::vector<double> gaps = BruteForce(q).gaps(pose);
  const double threshold = 10.0;  // every pair
  auto sorted = [](const std::vector<LeafContact>& got) {
    return std::is_sorted(got.begin(), got.end(),
                          [](const LeafContact& x, const LeafContact& y) { return x.gap < y.gap; });
  };
  std::vector<LeafContact> out;
  q.contacts(pose, threshold, out);
  EXPECT_EQ(out.size(), cap);
  EXPECT_TRUE(sorted(out));
  q.contactsNear(pose, threshold, 0.01, out);
  EXPECT_EQ(out.size(), cap);
  EXPECT_TRUE(sorted(out));
  const double covered = q.nearCoveredReach(pose);
  EXPECT_LT(covered, threshold);
  EXPECT_GT(covered, 0.0);
  const auto within = [covered](double g) { return g <= covered; };
  const long want = std::count_if(gaps.begin(), gaps.end(), within);
  const long got =
      std::count_if(out.begin(), out.end(), [&](const LeafContact& c) { return within(c.gap); });
  EXPECT_GT(want, 0);
  EXPECT_EQ(got, want);
}

}  // namespace
}  // namespace sc::detail
