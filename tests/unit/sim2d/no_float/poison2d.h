// SPDX-License-Identifier: MIT
// Forced in front of every file of the 2D step by the sim2d_no_float test:
// the standard headers the 2D lane adds to rewind_fixed's are seen first,
// then the fixed library's poison makes `float` and `double` name nothing.
#include <memory>
#include <string_view>
#include <type_traits>

#include "poison.h"
