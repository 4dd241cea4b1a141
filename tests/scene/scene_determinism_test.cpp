// SPDX-License-Identifier: MIT
// Parallel pair evaluation is deterministic: scenes run with 1, 2, 4 and the
// automatic number of threads list the same pairs with the same results, bit for
// bit and in the same order, every frame; a rerun reproduces the same hash.
// Also the thread setting through SceneSettings and SC_SCENE_MANAGER_THREADS.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "sc.h"
#include "scene_scenario.h"

namespace sc::test {
namespace {

/// FNV-1a over the bytes of every number of a pair list.
class ResultHash {
 public:
  void add(const std::vector<PairStatus>& pairs) {
    for (const PairStatus& p : pairs) {
      addInt(p.groups[0]);
      addInt(p.groups[1]);
      for (const DirectedResult& r : p.results) {
        addInt(static_cast<int>(r.code));
        addInt(r.target_object);
        addInt(r.opponent_object);
        addInt(r.target_piece);
        addInt(r.opponent_piece);
        addDouble(r.distance);
        for (const Vec3* v : {&r.normal, &r.point_on_target, &r.point_on_opponent, &r.tpdv, &r.rpdv,
                              &r.contact_position}) {
          for (int i = 0; i < 3; ++i) addDouble((*v)[i]);
        }
        for (int i = 0; i < 4; ++i) addDouble(r.contact_orientation.coeffs()[i]);
        for (const Feature* f : {&r.target_feature, &r.opponent_feature}) {
          addInt(static_cast<int>(f->type));
          for (int v : f->vertices) addInt(v);
        }
      }
    }
  }
  std::uint64_t value() const { return h_; }

 private:
  void addBytes(const void* data, size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h_ = (h_ ^ b[i]) * 1099511628211ull;
  }
  void addInt(int v) { addBytes(&v, sizeof v); }
  void addDouble(double v) { addBytes(&v, sizeof v); }
  std::uint64_t h_ = 14695981039346656037ull;
};

ScenarioOptions denseScenario() {
  ScenarioOptions o;
  o.seed = 77;
  o.groups = 250;
  o.statics = 20;
  o.max_distance = 0.6;
  o.density = 0.15;  // many close and penetrating pairs
  return o;
}

/// Runs the scenario on scenes with the given thread counts in lockstep, comparing
/// every frame against the first; returns the hash of the first scene's output.
std::uint64_t runLockstep(const std::vector<int>& threads, int frames, long* listed = nullptr) {
  const ScenarioOptions options = denseScenario();
  Scenario scenario(options);
  ReferenceScene state(options.kind);  // drives the scenario's choices
  std::vector<std::unique_ptr<Scene>> scenes;
  for (int t : threads) {
    scenes.push_back(std::make_unique<Scene>(options.kind));
    SceneSettings s;
    s.threads = t;
    EXPECT_TRUE(scenes.back()->setSettings(s).ok());
  }
  auto applyAll = [&](const std::vector<Op>& ops) {
    for (const Op& op : ops) {
      const bool ok = apply(state, op);
      for (auto& scene : scenes) EXPECT_EQ(apply(*scene, op), ok);
    }
  };
  applyAll(scenario.populate());
  ResultHash hash;
  long total = 0;
  for (int f = 0; f < frames; ++f) {
    applyAll(scenario.frame(state));
    for (auto& scene : scenes) EXPECT_TRUE(scene->update().ok());
    for (size_t k = 1; k < scenes.size(); ++k) {
      const std::string diff = firstDifference(scenes[k]->pairs(), scenes[0]->pairs());
      EXPECT_TRUE(diff.empty()) << "frame " << f << ", " << threads[k] << " threads vs "
                                << threads[0] << ": " << diff;
      if (!diff.empty()) return 0;
    }
    hash.add(scenes[0]->pairs());
    total += static_cast<long>(scenes[0]->pairs().size());
  }
  if (listed) *listed = total;
  return hash.value();
}

TEST(SceneDeterminism, OneTwoFourAndAutomaticThreadsGiveIdenticalOutputs) {
  const int frames = slowBuild() ? 25 : 80;
  long listed = 0;
  const std::uint64_t h = runLockstep({1, 2, 4, 0}, frames, &listed);
  // Enough pairs per frame for the workers to share them.
  EXPECT_GT(listed, 100L * frames);
  std::printf("[ hash     ] %d frames, %ld listed pairs, hash %016llx\n", frames, listed,
              static_cast<unsigned long long>(h));
  // A second run, four threads alone, reproduces the serial run's hash.
  EXPECT_EQ(runLockstep({4}, frames), h);
}

TEST(SceneThreads, SettingIsValidatedAndChangeableBetweenUpdates) {
  SceneSettings s;
  EXPECT_EQ(s.threads, 0);
  s.threads = -1;
  EXPECT_EQ(validate(s).code(), ErrorCode::InvalidArgument);
  s.threads = kMaxThreads + 1;
  EXPECT_EQ(validate(s).code(), ErrorCode::InvalidArgument);
  s.threads = kMaxThreads;
  EXPECT_TRUE(validate(s).ok());
  s.broadphase = static_cast<Broadphase>(7);
  EXPECT_EQ(validate(s).code(), ErrorCode::InvalidArgument);

  // Changing the count between updates changes nothing in the results.
  const ScenarioOptions options = denseScenario();
  Scenario scenario(options);
  ReferenceScene state(options.kind);
  Scene serial(options.kind), changing(options.kind);
  SceneSettings one;
  one.threads = 1;
  ASSERT_TRUE(serial.setSettings(one).ok());
  for (const Op& op : scenario.populate()) {
    const bool ok = apply(state, op);
    ASSERT_EQ(apply(serial, op), ok);
    ASSERT_EQ(apply(changing, op), ok);
  }
  const int counts[] = {3, 1, 2, 0, 4, 1, 2};
  for (int f = 0; f < 14; ++f) {
    for (const Op& op : scenario.frame(state)) {
      const bool ok = apply(state, op);
      ASSERT_EQ(apply(serial, op), ok);
      ASSERT_EQ(apply(changing, op), ok);
    }
    SceneSettings t = changing.settings();
    t.threads = counts[f % 7];
    ASSERT_TRUE(changing.setSettings(t).ok());
    ASSERT_TRUE(serial.update().ok());
    ASSERT_TRUE(changing.update().ok());
    ASSERT_EQ(firstDifference(changing.pairs(), serial.pairs()), "") << "frame " << f;
  }
}

TEST(ScSceneManagerThreads, AttributeRoundTripsAndRejectsOutOfRange) {
  SCSceneManager m(SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
  SCint threads = -5;
  EXPECT_EQ(m.GetAttributeInteger(SC_SCENE_MANAGER_THREADS, &threads), SC_NO_ERROR);
  EXPECT_EQ(threads, 0);
  EXPECT_EQ(m.SetAttributeInteger(SC_SCENE_MANAGER_THREADS, 3), SC_NO_ERROR);
  EXPECT_EQ(m.GetAttributeInteger(SC_SCENE_MANAGER_THREADS, &threads), SC_NO_ERROR);
  EXPECT_EQ(threads, 3);
  EXPECT_EQ(m.SetAttributeInteger(SC_SCENE_MANAGER_THREADS, -1), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(m.SetAttributeInteger(SC_SCENE_MANAGER_THREADS, 100000), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(m.SetAttributeDouble(SC_SCENE_MANAGER_THREADS, 2.0), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(m.GetAttributeInteger(SC_SCENE_MANAGER_THREADS, &threads), SC_NO_ERROR);
  EXPECT_EQ(threads, 3);  // a rejected call changes nothing
  EXPECT_EQ(m.GetAttributeInteger(SC_SCENE_MANAGER_THREADS, nullptr), SC_ERROR_INVALID_ARGUMENT);
  // The other integer attribute is untouched.
  SCint iterations = 0;
  EXPECT_EQ(m.GetAttributeInteger(SC_SCENE_MANAGER_MAX_ITERATION, &iterations), SC_NO_ERROR);
  EXPECT_EQ(iterations, kDefaultMaxIterations);
}

}  // namespace
}  // namespace sc::test
