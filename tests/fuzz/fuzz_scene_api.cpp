// SPDX-License-Identifier: MIT
// Fuzzes SCSceneManager with byte-driven call sequences: objects added and deleted
// under random ids, groups, activities (valid and not), transformations (valid,
// NaN, inf, huge, raw bits), attributes, UpdateStatus and GetStatus with random
// indices; every update's results go through the checks of fuzz_common.h.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "fuzz_common.h"
#include "sc.h"

namespace {

using sc::fuzz::ByteReader;

/// The small objects every run starts from; preprocessed once into cache files so
/// each run only loads them.
struct Shape {
  SCenum type;
  std::vector<double> vertices;
  std::vector<SCint> triangles;
  std::string cache;
};

std::vector<Shape> makeShapes() {
  const std::vector<double> box = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1,
                                   -1, -1, 1,  1, -1, 1,  1, 1, 1,  -1, 1, 1};
  const std::vector<SCint> box_tris = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                       1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
  const std::vector<double> tetra = {1, 1, 1, -1, -1, 1, -1, 1, -1, 1, -1, -1};
  const std::vector<SCint> tetra_tris = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};
  // An L-shaped prism (non-convex): the L in the xy plane, extruded along z.
  const double l2d[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  std::vector<double> l;
  for (double z : {0.0, 0.5})
    for (const auto& p : l2d) l.insert(l.end(), {p[0] - 0.7, p[1] - 0.7, z});
  std::vector<SCint> l_tris = {0, 2, 1, 0, 3, 2, 0, 5, 3, 3, 5, 4,        // bottom
                               6, 7, 8, 6, 8, 9, 6, 9, 11, 9, 10, 11};   // top
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    l_tris.insert(l_tris.end(), {i, j, j + 6, i, j + 6, i + 6});
  }
  const std::vector<double> square = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<SCint> square_tris = {0, 1, 2, 0, 2, 3};
  return {{SC_OBJECT_TYPE_CLOSED_POLYHEDRON, box, box_tris, {}},
          {SC_OBJECT_TYPE_CLOSED_POLYHEDRON, tetra, tetra_tris, {}},
          {SC_OBJECT_TYPE_CLOSED_POLYHEDRON, l, l_tris, {}},
          {SC_OBJECT_TYPE_TRIANGLE_SOUP, square, square_tris, {}},
          {SC_OBJECT_TYPE_TRIANGLE_SOUP, box, box_tris, {}},
          {SC_OBJECT_TYPE_TRIANGLE_SOUP, l, l_tris, {}}};
}

/// Removes the shapes' cache files when the fuzzer exits.
struct ShapeFiles {
  std::vector<Shape> shapes;
  std::string directory;
  ~ShapeFiles() {
    for (const Shape& s : shapes) std::remove(s.cache.c_str());
    rmdir(directory.c_str());
  }
};

const std::vector<Shape>& shapes() {
  static const ShapeFiles all = [] {
    std::vector<Shape> s = makeShapes();
    char dir[] = "/tmp/sc_fuzz_scene_XXXXXX";
    if (mkdtemp(dir) == nullptr) sc::fuzz::fail("mkdtemp failed");
    for (std::size_t i = 0; i < s.size(); ++i) {
      s[i].cache = std::string(dir) + "/shape" + std::to_string(i) + ".scc";
      SCObject o(s[i].type);
      if (o.AddTriangles(s[i].vertices.data(), static_cast<SCint>(s[i].vertices.size() / 3),
                         s[i].triangles.data(), static_cast<SCint>(s[i].triangles.size() / 3),
                         s[i].cache.c_str()) != SC_NO_ERROR)
        sc::fuzz::fail("fixed shape rejected", static_cast<double>(i));
    }
    return ShapeFiles{std::move(s), dir};
  }();
  return all.shapes;
}

constexpr int kMaxOps = 48;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

constexpr SCenum kTransformTypes[] = {
    SC_POSITION_ORIGIN,           SC_POSITION_WORLD_CENTER,     SC_POSITION_LOCAL_CENTER,
    SC_POSITION_NEW_WORLD_CENTER, SC_POSITION_NEW_LOCAL_CENTER, SC_ORIENTATION_QUATERNION,
    SC_ORIENTATION_MATRIX,        SC_TRANSFORMATION_MATRIX};
constexpr SCenum kActivities[] = {SC_ACTIVITY_ACTIVE,         SC_ACTIVITY_SLEEPING,
                                  SC_ACTIVITY_PASSIVE,        SC_ACTIVITY_INACTIVE,
                                  SC_ACTIVITY_ONE_WAY_ACTIVE, SC_ACTIVITY_ONE_WAY_INACTIVE};
constexpr SCenum kAttributes[] = {SC_SCENE_MANAGER_MAX_DISTANCE,
                                  SC_SCENE_MANAGER_TOLERANCE,
                                  SC_SCENE_MANAGER_SAFETY_COEFFICIENT,
                                  SC_SCENE_MANAGER_MAX_ITERATION,
                                  SC_SCENE_MANAGER_ROTATION_MODE,
                                  SC_SCENE_MANAGER_FORCE_STIFFNESS,
                                  SC_SCENE_MANAGER_TORQUE_STIFFNESS,
                                  SC_SCENE_MANAGER_THREADS,
                                  SC_SCENE_MANAGER_RESOLVE_INITIAL_INTERSECTION,
                                  SC_SCENE_MANAGER_CONTACT_POINTS,
                                  SC_SCENE_MANAGER_TELEPORT_DISTANCE,
                                  SC_SCENE_MANAGER_PROXY_TRAVEL_RATIO};
constexpr SCenum kStatusTypes[] = {
    SC_STATUS_COUNT,      SC_STATUS_RESULT,      SC_GROUP_ID,           SC_OBJECT_ID,
    SC_PIECE_ID,          SC_DISTANCE,           SC_CONTACT_NORMAL,     SC_POINT_ON_TARGET,
    SC_POINT_ON_OPPONENT, SC_FEATURE_TYPE,       SC_FEATURE_ON_TARGET,  SC_FEATURE_ON_OPPONENT,
    SC_TPD_VECTOR,        SC_RPD_VECTOR,         SC_CONTACT_POSITION,   SC_CONTACT_ORIENTATION,
    SC_CONTACT_POINT_COUNT, SC_CONTACT_POINTS};

template <class T, std::size_t N>
T pickOr(ByteReader& in, const T (&values)[N]) {
  const int i = in.pick(static_cast<int>(N) + 1);
  return i < static_cast<int>(N) ? values[i] : in.raw<T>();
}

SCint objectId(ByteReader& in) {
  const int i = in.pick(8);
  return i == 7 ? in.raw<SCint>() : i % 6;
}
SCint groupId(ByteReader& in) {
  const int i = in.pick(8);
  return i == 7 ? in.raw<SCint>() : i == 6 ? SC_GROUP_STATIC : i % 4;
}

/// 16 numbers for any transformation type: a valid one (small positions, a proper
/// rotation) or one with a NaN, an inf, a huge value or raw bits somewhere.
void transformValues(ByteReader& in, double* v) {
  const sc::Vec3 axis(in.u8() - 127.5, in.u8() - 127.5, in.u8() - 127.5);
  const double angle = in.u8() / 40.0;
  const sc::Quat q(Eigen::AngleAxisd(angle, axis.normalized()));
  const sc::Vec3 t(static_cast<std::int8_t>(in.u8()) / 16.0, static_cast<std::int8_t>(in.u8()) / 16.0,
                   static_cast<std::int8_t>(in.u8()) / 16.0);
  const sc::Mat3 r = q.toRotationMatrix();
  // Fill for the widest reading: positions use v[0..2], quaternions v[0..3], the
  // 3x3 matrix v[0..8] and the 4x4 matrix all 16 (column-major).
  for (int i = 0; i < 16; ++i) v[i] = 0.0;
  const int layout = in.pick(3);
  if (layout == 0) {
    for (int i = 0; i < 3; ++i) v[i] = t[i];
  } else if (layout == 1) {
    v[0] = q.w(), v[1] = q.x(), v[2] = q.y(), v[3] = q.z();
  } else {
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) v[4 * c + k] = r(k, c);
    for (int k = 0; k < 3; ++k) v[12 + k] = t[k];
    v[15] = 1.0;
  }
  switch (in.pick(6)) {
    case 0: v[in.pick(16)] = kNaN; break;
    case 1: v[in.pick(16)] = in.flag() ? kInf : -kInf; break;
    case 2: v[in.pick(16)] = in.flag() ? 1e300 : -1e300; break;
    case 3:
      for (int i = 0; i < 16; ++i) v[i] = in.raw<double>();
      break;
    default: break;  // valid
  }
}

void setTransformation(SCSceneManager& scene, ByteReader& in) {
  const SCint gid = groupId(in);
  const SCenum type = pickOr(in, kTransformTypes);
  double v[16];
  transformValues(in, v);
  if (in.flag()) {
    float f[16];
    for (int i = 0; i < 16; ++i) f[i] = static_cast<float>(v[i]);
    scene.SetTransformation(gid, type, f);
  } else {
    scene.SetTransformation(gid, type, v);
  }
}

void getTransformation(const SCSceneManager& scene, ByteReader& in) {
  const SCint gid = groupId(in);
  const SCenum type = pickOr(in, kTransformTypes);
  double d[16] = {};
  float f[16] = {};
  const SCint code = scene.GetTransformation(gid, type, d);
  if (scene.GetTransformation(gid, type, f) != code)
    sc::fuzz::fail("float and double GetTransformation disagree");
  if (code == SC_NO_ERROR) sc::fuzz::requireFinite(d, 16, "group transformation not finite");
}

void setAttribute(SCSceneManager& scene, ByteReader& in) {
  static constexpr double kDoubles[] = {-1.0, 0.0, 1e-9, 1e-3, 0.01, 0.1, 0.49, 1.0,
                                        10.0, 1e300, kInf, -kInf, kNaN};
  // No raw integers: a max-iteration count of 2^31 is valid and only slow.
  static constexpr SCint kInts[] = {-1, 0, 1, 2, 3, 10, 100, 257};
  static constexpr SCenum kEnums[] = {SC_ROTATION_MODE_NONE, SC_ROTATION_MODE_INPUT,
                                      SC_ROTATION_MODE_FREE, SC_ROTATION_MODE_MIX, 0};
  const SCenum attribute = pickOr(in, kAttributes);
  switch (in.pick(3)) {
    case 0: scene.SetAttributeDouble(attribute, pickOr(in, kDoubles)); break;
    case 1: scene.SetAttributeInteger(attribute, kInts[in.pick(8)]); break;
    default: scene.SetAttributeEnum(attribute, pickOr(in, kEnums)); break;
  }
}

void getAttribute(const SCSceneManager& scene, ByteReader& in) {
  const SCenum attribute = pickOr(in, kAttributes);
  double d = 0.0;
  SCint i = 0;
  SCenum e = 0;
  scene.GetAttributeDouble(attribute, &d);
  scene.GetAttributeInteger(attribute, &i);
  scene.GetAttributeEnum(attribute, &e);
  if (std::isnan(d)) sc::fuzz::fail("attribute read back as NaN", attribute);
}

/// GetStatus with a random type, index (possibly out of range) and direction;
/// the buffer is as large as the type needs.
void getStatus(SCSceneManager& scene, ByteReader& in) {
  SCint count = 0;
  scene.GetStatus(SC_STATUS_COUNT, &count);
  const int choice = in.pick(4);
  const SCint index = choice == 0 ? -1 : choice == 1 ? count : choice == 2 ? in.raw<SCint>()
                                                       : (count > 0 ? in.u8() % count : 0);
  const bool reverse = in.flag();
  const SCenum type = pickOr(in, kStatusTypes);
  SCint contacts = 0;
  if (type == SC_CONTACT_POINTS &&
      scene.GetStatus(SC_CONTACT_POINT_COUNT, &contacts, index, reverse) != SC_NO_ERROR)
    contacts = 0;
  std::vector<double> d(16 + 10 * static_cast<std::size_t>(contacts), 0.0);
  std::vector<float> f(d.size(), 0.0f);
  SCint ints[4] = {};
  scene.GetStatus(type, ints, index, reverse);
  if (scene.GetStatus(type, d.data(), index, reverse) == SC_NO_ERROR)
    sc::fuzz::requireFinite(d.data(), static_cast<int>(d.size()), "GetStatus real not finite");
  scene.GetStatus(type, f.data(), index, reverse);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<Shape>& all = shapes();
  ByteReader in(data, size);
  const bool soup_scene = in.flag();
  auto scene = std::make_unique<SCSceneManager>(soup_scene ? SC_SCENE_MANAGER_TRIANGLE_SOUP
                                                           : SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
  std::vector<std::unique_ptr<SCObject>> objects;
  for (const Shape& s : all) {
    objects.push_back(std::make_unique<SCObject>(s.type));
    if (objects.back()->AddTriangles(s.vertices.data(), static_cast<SCint>(s.vertices.size() / 3),
                                     s.triangles.data(),
                                     static_cast<SCint>(s.triangles.size() / 3),
                                     s.cache.c_str()) != SC_NO_ERROR)
      sc::fuzz::fail("fixed shape rejected on reload");
  }
  objects.push_back(std::make_unique<SCObject>(SC_OBJECT_TYPE_CLOSED_POLYHEDRON));  // empty

  for (int op = 0; op < kMaxOps && !in.empty(); ++op) {
    switch (in.pick(16)) {
      case 0:
      case 1: {
        const SCint id = objectId(in);
        const int which = in.pick(static_cast<int>(objects.size()) + 1);
        scene->AddObject(id, which < static_cast<int>(objects.size()) ? objects[which].get()
                                                                      : nullptr);
        break;
      }
      case 2: scene->DeleteObject(objectId(in)); break;
      case 3: {
        const SCint gid = groupId(in);
        scene->AddObjectToGroup(gid, objectId(in));
        break;
      }
      case 4: {
        const SCint gid = groupId(in);
        const SCint id = objectId(in);
        if (in.flag())
          scene->DeleteObjectFromGroup(gid, id);
        else
          scene->DeleteFromGroup(gid, id);
        break;
      }
      case 5:
      case 6: setTransformation(*scene, in); break;
      case 7: getTransformation(*scene, in); break;
      case 8: {
        const SCint id = objectId(in);
        scene->SetActivityObject(id, pickOr(in, kActivities));
        break;
      }
      case 9: {
        const SCint gid = groupId(in);
        scene->SetActivityGroup(gid, pickOr(in, kActivities));
        break;
      }
      case 10: {
        const SCint a = groupId(in);
        const SCint b = groupId(in);
        scene->SetActivityPair(a, b, pickOr(in, kActivities));
        break;
      }
      case 11: setAttribute(*scene, in); break;
      case 12: getAttribute(*scene, in); break;
      case 13: {
        const SCint code = scene->UpdateStatus();
        if (code != SC_NO_ERROR) sc::fuzz::fail("UpdateStatus failed", code);
        sc::fuzz::checkScene(*scene);
        break;
      }
      case 14: getStatus(*scene, in); break;
      default: {
        // The object's own transformation: refused while it is in a scene.
        SCObject& o = *objects[static_cast<std::size_t>(in.pick(static_cast<int>(objects.size())))];
        const SCenum type = pickOr(in, kTransformTypes);
        double v[16];
        transformValues(in, v);
        o.SetTransformation(type, v);
        double out[16] = {};
        if (o.GetTransformation(type, out) == SC_NO_ERROR)
          sc::fuzz::requireFinite(out, 16, "object transformation not finite");
        break;
      }
    }
  }
  // Either order of destruction must be clean: objects leave the scene, or the
  // scene releases them.
  if (in.flag()) scene.reset();
  objects.clear();
  return 0;
}
