// SPDX-License-Identifier: MIT
// Shared by the fuzz targets: a front-to-back byte reader (so seeds are easy to
// write by hand) and checks of everything an SCSceneManager reports.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

#include "penetration/result_invariants.h"
#include "sc.h"

namespace sc::fuzz {

/// Reads the input from the front; past the end every read yields zero bytes.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  bool empty() const { return pos_ >= size_; }
  std::size_t remaining() const { return empty() ? 0 : size_ - pos_; }

  std::uint8_t u8() { return empty() ? 0 : data_[pos_++]; }
  bool flag() { return (u8() & 1) != 0; }
  /// `n` raw bytes into `out` (zeros past the end).
  void bytes(void* out, std::size_t n) {
    auto* o = static_cast<std::uint8_t*>(out);
    for (std::size_t i = 0; i < n; ++i) o[i] = u8();
  }
  template <class T>
  T raw() {
    T v;
    bytes(&v, sizeof v);
    return v;
  }
  /// One of `n` choices, from one byte.
  int pick(int n) { return static_cast<int>(u8() % static_cast<unsigned>(n)); }
  const std::uint8_t* rest() const { return data_ + pos_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

/// Stops the fuzzer with a message: libFuzzer reports the abort as a crash and
/// saves the input.
[[noreturn]] inline void fail(const char* what, double value = 0.0) {
  std::fprintf(stderr, "fuzz invariant broken: %s (%g)\n", what, value);
  std::abort();
}

inline void requireFinite(const double* v, int n, const char* what) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) fail(what, v[i]);
}

/// True when some value is beyond float's range: a float read of it is refused
/// (SC_ERROR_INVALID_ARGUMENT, nothing written; docs/api.md, GetStatus).
inline bool beyondFloat(const double* d, int n) {
  for (int i = 0; i < n; ++i)
    if (std::fabs(d[i]) > std::numeric_limits<float>::max()) return true;
  return false;
}

/// A float read answers as the double one did, except that values beyond float's
/// range are refused; when it answers, its values are finite.
inline void requireFloatRead(SCint double_code, SCint float_code, const float* f,
                             const double* d, int n, const char* what) {
  if (double_code == SC_NO_ERROR && float_code == SC_ERROR_INVALID_ARGUMENT && beyondFloat(d, n))
    return;
  if (float_code != double_code) fail(what, float_code);
  if (float_code != SC_NO_ERROR) return;
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(f[i])) fail(what, d[i]);
}

inline FeatureType featureFromSc(SCint t) {
  return t == SC_FEATURE_FACE ? FeatureType::Face
         : t == SC_FEATURE_EDGE ? FeatureType::Edge
                                : FeatureType::Vertex;
}

inline ErrorCode errorFromSc(SCint code) {
  switch (code) {
    case SC_NO_ERROR: return ErrorCode::Ok;
    case SC_ERROR_NO_RESULT: return ErrorCode::NoResult;
    case SC_ERROR_INVALID_INITIAL_TRANSFORMATION: return ErrorCode::InvalidInitialTransformation;
    default: return ErrorCode::InvalidArgument;
  }
}

/// Reads one direction of one pair through every GetStatus type, in double and
/// float, and checks it: the documented return codes, finite values, and
/// detail::checkResult on the DirectedResult reassembled from the façade.
inline void checkDirection(SCSceneManager& scene, SCint index, bool reverse) {
  SCint code = -1;
  if (scene.GetStatus(SC_STATUS_RESULT, &code, index, reverse) != SC_NO_ERROR)
    fail("GetStatus(SC_STATUS_RESULT) failed on a listed pair");
  if (code != SC_NO_ERROR && code != SC_ERROR_NO_RESULT &&
      code != SC_ERROR_INVALID_INITIAL_TRANSFORMATION)
    fail("SC_STATUS_RESULT outside {ok, no result, invalid initial}", code);
  SCint groups[2];
  if (scene.GetStatus(SC_GROUP_ID, groups, index, reverse) != SC_NO_ERROR)
    fail("GetStatus(SC_GROUP_ID) failed");
  SCint status = -1;
  if (scene.GetStatus(SC_DIRECTION_STATUS, &status, index, reverse) != SC_NO_ERROR)
    fail("GetStatus(SC_DIRECTION_STATUS) failed");
  // No result: beyond the maximum distance, or a direction not computed (its target
  // group static or passive), which the status tells apart.
  const bool status_fits =
      code == SC_ERROR_NO_RESULT
          ? status == SC_DIRECTION_BEYOND_MAX_DISTANCE || status == SC_DIRECTION_NOT_COMPUTED
      : code == SC_ERROR_INVALID_INITIAL_TRANSFORMATION
          ? status == SC_DIRECTION_FIRST_SEEN_INTERSECTING
          : status >= SC_DIRECTION_SEPARATED && status <= SC_DIRECTION_LAGGING;
  if (!status_fits) fail("SC_DIRECTION_STATUS disagrees with SC_STATUS_RESULT", status);
  SCint contact_count = -1;
  if (scene.GetStatus(SC_CONTACT_POINT_COUNT, &contact_count, index, reverse) != SC_NO_ERROR ||
      contact_count < 0)
    fail("GetStatus(SC_CONTACT_POINT_COUNT)", contact_count);
  {
    const std::size_t n = 10 * static_cast<std::size_t>(contact_count);
    std::vector<double> d(n + 1);
    std::vector<float> f(n + 1);
    if (scene.GetStatus(SC_CONTACT_POINTS, d.data(), index, reverse) != SC_NO_ERROR)
      fail("GetStatus(SC_CONTACT_POINTS) failed");
    requireFinite(d.data(), static_cast<int>(n), "contact point not finite");
    requireFloatRead(SC_NO_ERROR, scene.GetStatus(SC_CONTACT_POINTS, f.data(), index, reverse),
                     f.data(), d.data(), static_cast<int>(n), "float contact points");
  }

  static constexpr SCenum kIntTypes[] = {SC_OBJECT_ID, SC_PIECE_ID, SC_FEATURE_TYPE,
                                         SC_FEATURE_ON_TARGET, SC_FEATURE_ON_OPPONENT};
  static constexpr SCenum kRealTypes[] = {SC_DISTANCE, SC_CONTACT_NORMAL, SC_POINT_ON_TARGET,
                                          SC_POINT_ON_OPPONENT, SC_TPD_VECTOR, SC_RPD_VECTOR,
                                          SC_CONTACT_POSITION, SC_CONTACT_ORIENTATION};
  SCint ints[5][3] = {};
  double reals[8][4] = {};
  for (int t = 0; t < 5; ++t)
    if (scene.GetStatus(kIntTypes[t], ints[t], index, reverse) != code)
      fail("integer GetStatus disagrees with SC_STATUS_RESULT", kIntTypes[t]);
  for (int t = 0; t < 8; ++t) {
    float f[4] = {};
    if (scene.GetStatus(kRealTypes[t], reals[t], index, reverse) != code)
      fail("real GetStatus disagrees with SC_STATUS_RESULT", kRealTypes[t]);
    const int n = kRealTypes[t] == SC_DISTANCE ? 1 : kRealTypes[t] == SC_CONTACT_ORIENTATION ? 4 : 3;
    requireFloatRead(code, scene.GetStatus(kRealTypes[t], f, index, reverse), f, reals[t], n,
                     "float GetStatus disagrees with the double one");
    if (code == SC_NO_ERROR) requireFinite(reals[t], n, "GetStatus real not finite");
  }
  if (code != SC_NO_ERROR) return;

  DirectedResult r;
  r.code = errorFromSc(code);
  r.target_piece = ints[1][0];
  r.opponent_piece = ints[1][1];
  r.target_feature.type = featureFromSc(ints[2][0]);
  r.opponent_feature.type = featureFromSc(ints[2][1]);
  for (int i = 0; i < 3; ++i) {
    r.target_feature.vertices[i] = ints[3][i];
    r.opponent_feature.vertices[i] = ints[4][i];
  }
  r.distance = reals[0][0];
  r.normal = Vec3(reals[1][0], reals[1][1], reals[1][2]);
  r.point_on_target = Vec3(reals[2][0], reals[2][1], reals[2][2]);
  r.point_on_opponent = Vec3(reals[3][0], reals[3][1], reals[3][2]);
  r.tpdv = Vec3(reals[4][0], reals[4][1], reals[4][2]);
  r.rpdv = Vec3(reals[5][0], reals[5][1], reals[5][2]);
  r.contact_position = Vec3(reals[6][0], reals[6][1], reals[6][2]);
  r.contact_orientation = Quat(reals[7][0], reals[7][1], reals[7][2], reals[7][3]);
  if (Status s = detail::checkResult(r); !s.ok()) {
    std::fprintf(stderr, "pair %d reverse %d: %s\n", index, reverse ? 1 : 0, s.message().c_str());
    fail("checkResult");
  }
}

/// Every listed pair, both directions.
inline void checkScene(SCSceneManager& scene) {
  SCint count = -1;
  if (scene.GetStatus(SC_STATUS_COUNT, &count) != SC_NO_ERROR || count < 0)
    fail("SC_STATUS_COUNT", count);
  for (SCint i = 0; i < count; ++i) {
    checkDirection(scene, i, false);
    checkDirection(scene, i, true);
  }
}

}  // namespace sc::fuzz
