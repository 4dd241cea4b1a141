#pragma once
#include "smartcollision/model.h"
