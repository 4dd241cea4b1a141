// SPDX-License-Identifier: MIT
// Shared pieces of the stability matrix (bench/stability_matrix.cpp): a cell of the
// matrix, oriented boxes and their exact penetration depth.
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include "smartcollision/model.h"
#include "smartcollision/types.h"

namespace stab {

using sc::Mat3;
using sc::Vec3;

/// One measured cell. `outcome` is one word (pass, wrong, NaN, exception, crash,
/// hang, missed, tunnelled, exploded, fell, stuck, n/a); value / error as measured.
struct Cell {
  std::string row;
  std::string column;
  std::string outcome;
  double value = std::nan("");
  double error = std::nan("");
  std::string note;
};

/// An oriented box in the world: centre, rotation (columns = its axes), half extents.
struct Box {
  Vec3 half = Vec3::Constant(0.5);
  Mat3 rotation = Mat3::Identity();
  Vec3 centre = Vec3::Zero();
  Vec3 support(const Vec3& d) const;  ///< farthest corner along d
};

/// Closed, outward-wound triangle mesh of a box centred at the origin.
sc::MeshData boxMesh(const Vec3& half);

/// Exact penetration depth of two boxes (the translation of least length that
/// separates them): the Minkowski difference of two boxes only has facets normal to
/// a face of either box or to the cross product of an edge of each, so the least
/// overlap over those 15 directions is exact. <= 0 when they are apart (then minus
/// a lower bound of the gap); `axis` receives the direction, from a towards b.
double boxDepth(const Box& a, const Box& b, Vec3* axis = nullptr);

Mat3 rotationZ(double radians);

/// Outcome of a depth measured against the truth, with the same threshold for all.
inline constexpr double kPassError = 2e-3;  // two SmartCollision tolerances [m]

}  // namespace stab
