// SPDX-License-Identifier: MIT
// Dynamics rows of the stability matrix (thin wall, stiff penalty, tower, mass ratio,
// overlap recovery) in small Bullet worlds.
#pragma once
#include <vector>

#include "stability_common.h"

namespace stab {

std::vector<Cell> runDynamicsRows();

}  // namespace stab
