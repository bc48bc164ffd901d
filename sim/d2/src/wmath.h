// SPDX-License-Identifier: MIT
#pragma once
// The step's files include the working arithmetic by this short name.
#include "rewind/sim2d/detail/wmath.h"
