// SPDX-License-Identifier: MIT
// Everything of the Bullet plugin in one include.
#pragma once

#include "smartcollision/bullet/mass_properties.h"
#include "smartcollision/bullet/plugin.h"
#include "smartcollision/bullet/sc_bullet_shape.h"
#include "smartcollision/bullet/sc_dynamics_world.h"
#include "smartcollision/bullet/settings.h"
#include "smartcollision/bullet/stacking_solver.h"
