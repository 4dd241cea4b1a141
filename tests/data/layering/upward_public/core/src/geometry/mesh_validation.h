#pragma once
#include "smartcollision/mesh.h"
