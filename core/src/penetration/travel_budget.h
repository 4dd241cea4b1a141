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

}  // namespace sc::detail
