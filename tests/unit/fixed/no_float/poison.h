// SPDX-License-Identifier: MIT
// Forced in front of every file of rewind_fixed by check_no_float.cmake.
// The standard headers the library uses (and status.h) are included first,
// so their own floating-point declarations are already seen; after that,
// the words `float` and `double` (and so `long double`) name nothing, and
// any use of them in the library's own text fails to compile. A library
// file that includes a standard header missing from this list fails too:
// add the header here.
#include <algorithm>
#include <array>
#include <compare>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rewind/core/status.h"

#define float rwd_fixed_forbids_float
#define double rwd_fixed_forbids_double
