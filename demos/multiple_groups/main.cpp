// SPDX-License-Identifier: MIT
// Multiple groups (manual's SmartCollisionMultipleGroupTest) through the plain scene
// API of sc.h: six objects in four groups plus the static group, with different
// activities, moving along scripted paths. Each object is coloured by its status:
//   red     penetrating (distance <= 0) in some computed direction
//   yellow  within the warning distance (0 < d <= 0.3)
//   green   farther apart
//   grey    in no computed direction
// Groups:
//   1 ACTIVE   objects 10 (box) and 11 (octahedron, its object INACTIVE: never computed)
//   2 ACTIVE   object 20 (box); the pair (1, 2) is ONE_WAY_INACTIVE from 1: only 2 -> 1
//   3 PASSIVE  object 30 (octahedron): an opponent only
//   4 SLEEPING object 40 (box): an opponent only, does not move
//   static     object 50 (the floor slab)
// --headless runs a fixed number of frames and writes a PNG and JSON metrics: the
// pair count the scene lists every frame against the count the activities imply.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "../common/cli.h"
#include "../common/viewer.h"
#include "sc.h"

namespace {

constexpr double kWarnDistance = 0.3;
constexpr double kFrameDt = 1.0 / 60.0;

struct Options : sc::demo::HeadlessOptions {
  Options() { seconds = 6.0; }
};

enum class Status { Grey, Green, Yellow, Red };

struct Shape {
  std::vector<double> vertices;
  std::vector<int> triangles;
  sc::demo::DrawMesh draw;
};

Shape boxShape(double hx, double hy, double hz) {
  Shape s;
  for (int i = 0; i < 8; ++i) {
    s.vertices.push_back(i & 1 ? hx : -hx);
    s.vertices.push_back(i & 2 ? hy : -hy);
    s.vertices.push_back(i & 4 ? hz : -hz);
  }
  s.triangles = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                 2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
  return s;
}

Shape octahedronShape(double r) {
  Shape s;
  s.vertices = {r, 0, 0, -r, 0, 0, 0, r, 0, 0, -r, 0, 0, 0, r, 0, 0, -r};
  s.triangles = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  return s;
}

void makeDraw(Shape& s) {
  s.draw.vertices.assign(s.vertices.begin(), s.vertices.end());
  s.draw.indices = s.triangles;
}

struct Object {
  int id = 0;
  int group = 0;
  Shape shape;
  std::unique_ptr<SCObject> sc;
  Status status = Status::Grey;
};

/// Activity of a group as the demo sets it (the static group is passive).
enum class Act { Active, Passive, Sleeping };

class Demo {
 public:
  Demo() : manager_(SC_SCENE_MANAGER_CLOSED_POLYHEDRA) {
    manager_.SetAttributeDouble(SC_SCENE_MANAGER_MAX_DISTANCE,
                                100.0);  // every candidate pair listed
    manager_.SetAttributeDouble(SC_SCENE_MANAGER_TOLERANCE, 0.01);
    manager_.SetAttributeInteger(SC_SCENE_MANAGER_MAX_ITERATION, 20);
    add(10, 1, boxShape(0.25, 0.25, 0.25), {0, 0, 0});
    add(11, 1, octahedronShape(0.3), {0.7, 0, 0});  // relative to object 10's frame
    add(20, 2, boxShape(0.2, 0.4, 0.2), {0, 0, 0});
    add(30, 3, octahedronShape(0.35), {0, 0, 0});
    add(40, 4, boxShape(0.3, 0.3, 0.3), {1.5, 0.3, 0});
    add(50, SC_GROUP_STATIC, boxShape(3.0, 0.1, 3.0), {0, -0.1, 0});
    check(manager_.SetActivityObject(11, SC_ACTIVITY_INACTIVE), "object 11 inactive");
    check(manager_.SetActivityGroup(3, SC_ACTIVITY_PASSIVE), "group 3 passive");
    check(manager_.SetActivityGroup(4, SC_ACTIVITY_SLEEPING), "group 4 sleeping");
    check(manager_.SetActivityPair(1, 2, SC_ACTIVITY_ONE_WAY_INACTIVE), "pair 1 -> 2 one way");
    acts_ = {{1, Act::Active},
             {2, Act::Active},
             {3, Act::Passive},
             {4, Act::Sleeping},
             {SC_GROUP_STATIC, Act::Passive}};
  }

  /// Table 8-1 plus the one-way override: is the direction target -> opponent computed?
  bool expectedDirection(int target, int opponent) const {
    if (target == 1 && opponent == 2) return false;  // ONE_WAY_INACTIVE
    return acts_.at(target) == Act::Active;          // any opponent: active, sleeping, passive
  }

  /// Group pairs with at least one computed direction (all candidates are within the
  /// maximum distance of 100).
  int expectedPairs() const {
    int n = 0;
    for (auto a = acts_.begin(); a != acts_.end(); ++a)
      for (auto b = std::next(a); b != acts_.end(); ++b)
        if (expectedDirection(a->first, b->first) || expectedDirection(b->first, a->first)) ++n;
    return n;
  }

  void step() {
    t_ += kFrameDt;
    const double t = t_;
    // Group 1: a circle of radius 1.5 at 0.3 m, dipping into the floor twice a turn.
    move(1, {1.5 * std::cos(0.8 * t), 0.32 + 0.12 * std::cos(1.6 * t), 1.5 * std::sin(0.8 * t)},
         0.5 * t);
    // Group 2: back and forth along z through the circle.
    move(2, {0.4, 0.5, 2.2 * std::sin(0.6 * t)}, 0.0);
    // Group 3 (passive): up and down at the centre.
    move(3, {-0.6, 0.5 + 0.4 * std::sin(1.1 * t), -0.4}, 0.7 * t);
    // Group 4 sleeps where it was put.
    if (manager_.UpdateStatus() != SC_NO_ERROR) ++update_errors_;
    evaluate();
    ++frames_;
  }

  void collect(std::vector<sc::demo::DrawItem>& items) const {
    for (const auto& o : objects_) {
      double m[16];
      o->sc->GetTransformation(SC_TRANSFORMATION_MATRIX, m);
      static const float colors[4][3] = {
          {0.6f, 0.6f, 0.6f}, {0.3f, 0.75f, 0.35f}, {0.95f, 0.8f, 0.2f}, {0.9f, 0.25f, 0.2f}};
      sc::demo::DrawItem item = sc::demo::drawItem(&o->shape.draw, m, colors[int(o->status)]);
      if (o->group == SC_GROUP_STATIC)  // the floor a little darker
        for (float& c : item.color) c *= 0.8f;
      items.push_back(item);
    }
  }

  std::string overlay() const {
    return sc::demo::overlayText(
        "t = %.2f s   pairs %d (activities imply %d)   directions %d\n"
        "group 1 active (object 11 inactive), 2 active (1->2 one-way inactive),\n"
        "3 passive, 4 sleeping, static floor\n"
        "red penetrating, yellow within %.1f, green apart, grey not computed",
        t_, last_pairs_, expectedPairs(), last_directions_, kWarnDistance);
  }

  std::string json() const {
    char buf[1024];
    std::snprintf(
        buf, sizeof(buf),
        "{\n  \"frames\": %d,\n  \"objects\": %zu,\n  \"groups\": 4,\n  \"expected_pairs\": %d,\n"
        "  \"pair_count_min\": %d,\n  \"pair_count_max\": %d,\n  \"direction_mismatches\": %d,\n"
        "  \"update_errors\": %d,\n  \"object_frames\": {\"red\": %d, \"yellow\": %d, \"green\": "
        "%d, "
        "\"grey\": %d},\n  \"never_computed_objects\": [%s],\n  \"penetrating_pairs_seen\": "
        "%zu\n}\n",
        frames_, objects_.size(), expectedPairs(), pairs_min_, pairs_max_, mismatches_,
        update_errors_, counts_[3], counts_[2], counts_[1], counts_[0], neverComputed().c_str(),
        penetrating_pairs_.size());
    return buf;
  }

 private:
  static void check(SCint code, const char* what) {
    if (code != SC_NO_ERROR) {
      std::fprintf(stderr, "%s: %s\n", what, SCGetErrorString(code));
      std::exit(1);
    }
  }

  void add(int id, int group, Shape shape, const std::array<double, 3>& position) {
    auto o = std::make_unique<Object>();
    o->id = id;
    o->group = group;
    o->shape = std::move(shape);
    makeDraw(o->shape);
    o->sc = std::make_unique<SCObject>(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
    check(o->sc->AddTriangles(o->shape.vertices.data(), int(o->shape.vertices.size() / 3),
                              o->shape.triangles.data(), int(o->shape.triangles.size() / 3)),
          "AddTriangles");
    check(o->sc->SetTransformation(SC_POSITION_ORIGIN, position.data()), "object position");
    check(manager_.AddObject(id, o->sc.get()), "AddObject");
    if (group != SC_GROUP_STATIC) check(manager_.AddObjectToGroup(group, id), "AddObjectToGroup");
    objects_.push_back(std::move(o));
  }

  void move(int group, const std::array<double, 3>& p, double yaw) {
    check(manager_.SetTransformation(group, SC_POSITION_ORIGIN, p.data()), "group position");
    const double q[4] = {std::cos(0.5 * yaw), 0.0, std::sin(0.5 * yaw), 0.0};
    check(manager_.SetTransformation(group, SC_ORIENTATION_QUATERNION, q), "group orientation");
  }

  void evaluate() {
    for (auto& o : objects_) o->status = Status::Grey;
    int count = 0;
    manager_.GetStatus(SC_STATUS_COUNT, &count);
    last_pairs_ = count;
    pairs_min_ = frames_ == 0 ? count : std::min(pairs_min_, count);
    pairs_max_ = frames_ == 0 ? count : std::max(pairs_max_, count);
    last_directions_ = 0;
    std::set<std::pair<int, int>> listed;
    for (int i = 0; i < count; ++i) {
      for (bool reverse : {false, true}) {
        int gids[2] = {0, 0}, result = SC_ERROR_NO_RESULT;
        manager_.GetStatus(SC_GROUP_ID, gids, i, reverse);
        manager_.GetStatus(SC_STATUS_RESULT, &result, i, reverse);
        if (!reverse) listed.insert({std::min(gids[0], gids[1]), std::max(gids[0], gids[1])});
        const bool computed = result != SC_ERROR_NO_RESULT;
        if (computed != expectedDirection(gids[0], gids[1])) ++mismatches_;
        if (computed) ++last_directions_;
        if (result != SC_NO_ERROR) continue;
        double d = 0.0;
        int ids[2] = {0, 0};
        manager_.GetStatus(SC_DISTANCE, &d, i, reverse);
        manager_.GetStatus(SC_OBJECT_ID, ids, i, reverse);
        const Status s = d <= 0.0             ? Status::Red
                         : d <= kWarnDistance ? Status::Yellow
                                              : Status::Green;
        if (s == Status::Red)
          penetrating_pairs_.insert({std::min(gids[0], gids[1]), std::max(gids[0], gids[1])});
        for (int id : ids)
          for (auto& o : objects_)
            if (o->id == id) {
              o->status = std::max(o->status, s);
              computed_.insert(id);
            }
      }
    }
    // A pair the activities imply but the scene did not list is a mismatch too.
    for (auto a = acts_.begin(); a != acts_.end(); ++a)
      for (auto b = std::next(a); b != acts_.end(); ++b) {
        const bool expected =
            expectedDirection(a->first, b->first) || expectedDirection(b->first, a->first);
        if (expected !=
            (listed.count({std::min(a->first, b->first), std::max(a->first, b->first)}) > 0))
          ++mismatches_;
      }
    for (const auto& o : objects_) ++counts_[int(o->status)];
  }

  std::string neverComputed() const {
    std::string s;
    for (const auto& o : objects_)
      if (computed_.count(o->id) == 0) s += (s.empty() ? "" : ", ") + std::to_string(o->id);
    return s;
  }

  SCSceneManager manager_;
  std::vector<std::unique_ptr<Object>> objects_;
  std::map<int, Act> acts_;
  double t_ = 0.0;
  int frames_ = 0, last_pairs_ = 0, last_directions_ = 0, pairs_min_ = 0, pairs_max_ = 0;
  int mismatches_ = 0, update_errors_ = 0;
  int counts_[4] = {0, 0, 0, 0};  ///< object-frames per Status
  std::set<int> computed_;
  std::set<std::pair<int, int>> penetrating_pairs_;
};

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    if (!sc::demo::readHeadlessOption(argc, argv, i, o)) {
      std::fprintf(stderr, "usage: %s [--headless [--seconds S] [--png F] [--json F]]\n", argv[0]);
      return false;
    }
  }
  return o.seconds > 0.0 && std::isfinite(o.seconds);
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (!parse(argc, argv, options)) return 2;
  Demo demo;
  sc::demo::ViewerCallbacks cb;
  cb.collect = [&](std::vector<sc::demo::DrawItem>& items) { demo.collect(items); };
  cb.overlay = [&] { return demo.overlay(); };
  if (options.headless) {
    const long frames = std::lround(options.seconds / kFrameDt);
    for (long i = 0; i < frames; ++i) demo.step();
    const std::string metrics = demo.json();
    if (!sc::demo::emitMetrics(metrics, options.json)) return 1;
    if (!options.png.empty() && !sc::demo::renderToPng(argc, argv, cb, 0.3f, 7.0f, options.png))
      return 1;
    return 0;
  }
  cb.step = [&] { demo.step(); };
  sc::demo::runViewer(argc, argv, "SmartCollision multiple groups", cb, 0.3f, 7.0f);
  return 0;
}
