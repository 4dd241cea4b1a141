// SPDX-License-Identifier: MIT
// Fuzzes SCObject::AddTriangles with arbitrary arrays (double and float, any
// counts and indices, any object type), then uses the object in a scene against
// a fixed tetrahedron and checks every status it reports.
#include <cmath>
#include <cstdint>
#include <vector>

#include "fuzz_common.h"
#include "sc.h"

namespace {

using sc::fuzz::ByteReader;

constexpr int kMaxCount = 64;

/// Vertices of a regular-ish tetrahedron (outward, counter-clockwise faces).
constexpr double kTetraVertices[] = {1, 1, 1, -1, -1, 1, -1, 1, -1, 1, -1, -1};
constexpr SCint kTetraTriangles[] = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};

/// One coordinate: a grid value (so closed meshes are reachable) times a power of
/// two, or raw bits (NaN, inf, denormals).
template <class Real>
Real coordinate(ByteReader& in, bool raw_bits, double scale) {
  if (raw_bits) return in.raw<Real>();
  return static_cast<Real>(static_cast<std::int8_t>(in.u8()) * scale);
}

/// One AddTriangles call. Layout: flags, vertex count, triangle count, scale
/// exponent, coordinates, indices (byte 255 = a raw 32-bit index follows).
template <class Real>
void addPiece(SCObject& object, ByteReader& in, std::uint8_t flags) {
  int vertex_count = in.u8() % (kMaxCount + 1);
  int triangle_count = in.u8() % (kMaxCount + 1);
  const double scale = std::ldexp(1.0, in.u8() % 64 - 32);
  const bool raw_bits = (flags & 2) != 0;
  std::vector<Real> vertices(3 * static_cast<std::size_t>(vertex_count));
  for (Real& v : vertices) v = coordinate<Real>(in, raw_bits, scale);
  std::vector<SCint> triangles(3 * static_cast<std::size_t>(triangle_count));
  for (SCint& t : triangles) {
    const std::uint8_t b = in.u8();
    t = b == 255 ? in.raw<SCint>() : static_cast<SCint>(b % (vertex_count + 1));
  }
  // Arrays are exactly as long as the counts say; negative counts and null
  // pointers are asked for separately, with nothing to read behind them.
  const Real* vp = (flags & 4) != 0 ? nullptr : vertices.data();
  const SCint* tp = (flags & 8) != 0 ? nullptr : triangles.data();
  if ((flags & 16) != 0) vertex_count = -vertex_count - 1, vp = nullptr;
  if ((flags & 32) != 0) triangle_count = -triangle_count - 1, tp = nullptr;
  if (vp == nullptr && vertex_count > 0) vertex_count = vertices.empty() ? 0 : vertex_count;
  const SCint code = object.AddTriangles(vp, vertex_count, tp, triangle_count);
  if (code != SC_NO_ERROR && code != SC_ERROR_INVALID_ARGUMENT &&
      code != SC_ERROR_INVALID_GEOMETRY)
    sc::fuzz::fail("AddTriangles returned an undocumented code", code);
}

/// Every transformation of an object of a known type reads back finite; an object of
/// an unknown type refuses every call (docs/api.md) and writes nothing.
void checkObjectTransformations(const SCObject& object, SCenum object_type) {
  static constexpr SCenum kTypes[] = {SC_POSITION_ORIGIN, SC_POSITION_WORLD_CENTER,
                                      SC_POSITION_LOCAL_CENTER, SC_ORIENTATION_QUATERNION,
                                      SC_ORIENTATION_MATRIX, SC_TRANSFORMATION_MATRIX};
  const bool known = object_type == SC_OBJECT_TYPE_CLOSED_POLYHEDRON ||
                     object_type == SC_OBJECT_TYPE_TRIANGLE_SOUP;
  for (SCenum type : kTypes) {
    double d[16] = {};
    float f[16] = {};
    const SCint expected = known ? SC_NO_ERROR : SC_ERROR_INVALID_ARGUMENT;
    if (object.GetTransformation(type, d) != expected)
      sc::fuzz::fail("GetTransformation returned another code than documented", type);
    sc::fuzz::requireFinite(d, 16, "object transformation not finite");
    sc::fuzz::requireFloatRead(expected, object.GetTransformation(type, f), f, d, 16,
                               "float GetTransformation disagrees with the double one");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  const int kind = in.pick(4);
  const SCenum type = kind == 0   ? SC_OBJECT_TYPE_CLOSED_POLYHEDRON
                      : kind == 1 ? SC_OBJECT_TYPE_TRIANGLE_SOUP
                      : kind == 2 ? SC_OBJECT_TYPE_CLOSED_POLYHEDRON
                                  : in.raw<SCenum>();
  SCObject object(type);
  for (int call = 0; call < 2; ++call) {
    const std::uint8_t flags = in.u8();
    if ((flags & 1) != 0)
      addPiece<float>(object, in, flags);
    else
      addPiece<double>(object, in, flags);
  }
  checkObjectTransformations(object, type);

  // The object in a scene of its kind (or the other kind: AddObject must refuse
  // cleanly), placed near a fixed tetrahedron, through two updates.
  const bool soup = type == SC_OBJECT_TYPE_TRIANGLE_SOUP;
  const bool other_kind = in.flag();
  const bool soup_scene = soup != other_kind;
  SCSceneManager scene(soup_scene ? SC_SCENE_MANAGER_TRIANGLE_SOUP
                                  : SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
  SCObject tetra(soup_scene ? SC_OBJECT_TYPE_TRIANGLE_SOUP : SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  if (tetra.AddTriangles(kTetraVertices, 4, kTetraTriangles, 4) != SC_NO_ERROR)
    sc::fuzz::fail("fixed tetrahedron rejected");
  if (scene.AddObject(2, &tetra) != SC_NO_ERROR) sc::fuzz::fail("AddObject(tetra) failed");
  if (scene.AddObject(1, &object) != SC_NO_ERROR) return 0;
  if (scene.AddObjectToGroup(1, 1) != SC_NO_ERROR) sc::fuzz::fail("AddObjectToGroup failed");
  for (int step = 0; step < 2; ++step) {
    double position[3];
    for (double& p : position) p = static_cast<std::int8_t>(in.u8()) / 16.0;
    double q[4] = {1.0, in.u8() / 255.0, 0.0, in.u8() / 255.0};
    if (scene.SetTransformation(1, SC_POSITION_WORLD_CENTER, position) != SC_NO_ERROR ||
        scene.SetTransformation(1, SC_ORIENTATION_QUATERNION, q) != SC_NO_ERROR)
      sc::fuzz::fail("valid SetTransformation refused");
    const SCint code = scene.UpdateStatus();
    if (code != SC_NO_ERROR) sc::fuzz::fail("UpdateStatus failed", code);
    sc::fuzz::checkScene(scene);
    checkObjectTransformations(object, type);
  }
  return 0;
}
