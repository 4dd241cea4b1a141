// SPDX-License-Identifier: MIT
// Peer penetration queries on two boxes, each run in a child process so that a
// crash, an abort or an endless loop of a peer becomes a recorded outcome.
#pragma once
#include <string>

#include "stability_common.h"

namespace stab {

enum class PeerStatus { Penetrating, Apart, Exception, Crash, Hang, Missing };

struct PeerOut {
  PeerStatus status = PeerStatus::Missing;
  double depth = 0.0;  ///< when Penetrating (may be NaN); 0 or minus the gap when Apart
  std::string message;
};

PeerOut fclSignedDistance(const Box& a, const Box& b);
PeerOut fclCollide(const Box& a, const Box& b);
PeerOut ccdEpa(const Box& a, const Box& b);
PeerOut ccdMpr(const Box& a, const Box& b);
PeerOut bulletGjkEpa(const Box& a, const Box& b);

/// The cell of a peer's answer against the exact depth `truth` (>= 0).
Cell peerCell(const std::string& row, const std::string& column, const PeerOut& out,
              double truth);

}  // namespace stab
