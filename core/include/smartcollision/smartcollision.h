// SPDX-License-Identifier: MIT
// The whole modern API.
#pragma once

#include "smartcollision/collision.h"
#include "smartcollision/group.h"
#include "smartcollision/mesh.h"
#include "smartcollision/model.h"
#include "smartcollision/pair_settings.h"
#include "smartcollision/pair_tracker.h"
#include "smartcollision/placement.h"
#include "smartcollision/scene.h"
#include "smartcollision/settings.h"
#include "smartcollision/types.h"
