// SPDX-License-Identifier: MIT
// How far the proxy may still move in one update (PairSettings::proxy_travel_ratio).
#pragma once

#include "smartcollision/types.h"

namespace sc::detail {

/// Each step of the proxy is cut to what is left before it is swept (a shorter
/// sweep costs less) and charged after.
struct TravelBudget {
  double left = kInfinity;
  bool spent = false;  ///< a step was cut short: the proxy lags behind its minimum

  /// The fraction of a step `length` long that may be taken (1: all of it).
  double share(double length) const { return length > left ? left / length : 1.0; }
  /// Charges a step taken; `cut` when it was cut short.
  void charge(double length, bool cut) {
    left = length >= left ? 0.0 : left - length;
    spent = spent || cut;
  }
};

/// The least fraction of a step at which a linear row short by `short_by` at its
/// start, and gaining `rate` over the whole step, holds: 0 when it holds already, 1
/// when only the step's end is known to satisfy it.
inline double holdFraction(double short_by, double rate) {
  if (short_by <= 0.0) return 0.0;
  return rate > short_by ? short_by / rate : 1.0;
}

}  // namespace sc::detail
