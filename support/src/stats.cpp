// SPDX-License-Identifier: MIT
#include "sc_support/stats.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace sc::support {

Quat randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  // In sequence, last first: the former Quat(n, n, n, n)'s order under GCC (the
  // order of arguments is unspecified; figures must not depend on the compiler).
  const double z = n(rng), y = n(rng), x = n(rng), w = n(rng);
  return Quat(w, x, y, z).normalized();
}

Vec3 randomDirection(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return randomVec3(n, rng).normalized();
}

double quantile(std::vector<double> samples, double q, QuantileRank rank) {
  if (samples.empty()) return std::nan("");
  std::sort(samples.begin(), samples.end());
  const double n = double(samples.size());
  const std::size_t i =
      rank == QuantileRank::Floor ? std::size_t(q * n) : std::size_t(std::lround(q * (n - 1.0)));
  return samples[std::min(samples.size() - 1, i)];
}

}  // namespace sc::support
