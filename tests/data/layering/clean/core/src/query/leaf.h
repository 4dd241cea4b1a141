#pragma once
#include "geometry/math_util.h"
#include "smartcollision/group.h"
