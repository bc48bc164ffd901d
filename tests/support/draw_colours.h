// SPDX-License-Identifier: MIT
#pragma once
// The colours a debug draw used, for the lanes' debug-draw tests.
#include <algorithm>
#include <vector>

#include "rewind/core/debug_draw.h"

namespace rwd::test_support {

/// Each colour of `out`'s lines once, ascending.
inline std::vector<rwd::DrawColor> line_colours(const rwd::DebugDrawBuffers& out) {
  std::vector<rwd::DrawColor> seen;
  for (const rwd::DrawVertex& v : out.lines) seen.push_back(v.color);
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  return seen;
}

/// `colours` ascending, to compare with line_colours().
inline std::vector<rwd::DrawColor> sorted(std::vector<rwd::DrawColor> colours) {
  std::sort(colours.begin(), colours.end());
  return colours;
}

}  // namespace rwd::test_support
