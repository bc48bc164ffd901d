// SPDX-License-Identifier: MIT
#pragma once
// The colours a debug draw used, for the lanes' debug-draw tests.
#include <algorithm>
#include <vector>

#include "rewind/sim/debug_draw.h"

namespace rwd::test_support {

/// Each colour of `out`'s lines once, ascending.
inline std::vector<sim::DrawColor> line_colours(const sim::DebugDrawBuffers& out) {
  std::vector<sim::DrawColor> seen;
  for (const sim::DrawVertex& v : out.lines) seen.push_back(v.color);
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  return seen;
}

/// `colours` ascending, to compare with line_colours().
inline std::vector<sim::DrawColor> sorted(std::vector<sim::DrawColor> colours) {
  std::sort(colours.begin(), colours.end());
  return colours;
}

}  // namespace rwd::test_support
