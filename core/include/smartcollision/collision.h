// SPDX-License-Identifier: MIT
// Pair-level collision and everything it is used with: the pair tracker
// (pair_tracker.h), its groups and models, and the settings a scene passes it
// (settings.h: SceneSettings is a PairSettings).
#pragma once

#include "smartcollision/model.h"
#include "smartcollision/pair_tracker.h"
#include "smartcollision/placement.h"
#include "smartcollision/settings.h"
