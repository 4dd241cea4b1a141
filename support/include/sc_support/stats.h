// SPDX-License-Identifier: MIT
// Random poses and the quantiles of measured samples, shared by the benches (one
// generator, std::mt19937_64, so that a seed gives the same cases everywhere).
#pragma once

#include <random>
#include <vector>

#include "smartcollision/types.h"

namespace sc::support {

/// Uniform random rotation: a normalised 4D Gaussian.
Quat randomRotation(std::mt19937_64& rng);
/// Uniform random unit vector: a normalised 3D Gaussian.
Vec3 randomDirection(std::mt19937_64& rng);

/// A vector of three draws of `d`, drawn last coordinate first: a fixed order (the
/// order of `Vec3(d(rng), d(rng), d(rng))`'s draws is the compiler's choice), the one
/// GCC took, so that the benches' earlier figures keep their cases.
template <class Distribution>
Vec3 randomVec3(Distribution& d, std::mt19937_64& rng) {
  const double z = d(rng), y = d(rng), x = d(rng);
  return Vec3(x, y, z);
}

/// Which sample a quantile q of n sorted samples is: floor(q n) (clamped to the last)
/// or the nearest rank round(q (n - 1)).
enum class QuantileRank { Floor, Nearest };

/// The q-quantile of `samples` (0 <= q <= 1); NaN when there are none.
double quantile(std::vector<double> samples, double q, QuantileRank rank = QuantileRank::Floor);

}  // namespace sc::support
