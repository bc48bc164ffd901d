// SPDX-License-Identifier: MIT
#pragma once
// The distance links of a rectangular cloth sheet, built from its grid:
// edges between neighbours along rows and columns, shear links across each
// cell's two diagonals, and bending links across each pair of edges in line
// (particles two apart). They come in colours: the links of one colour share
// no particle, so a colour's corrections can be applied in any order, or by
// several threads at once, with the same result. The colouring follows from
// the grid (parity of the row or column), so it is the same on every
// machine and needs no search.
#include <cstdint>
#include <vector>

#include "rewind/core/status.h"

namespace rwd::sim::soft {

enum class LinkKind : uint8_t { kEdge, kShear, kBend };

/// Two particles (indices into the sheet, row-major: row * columns + column)
/// held at `rest` metres apart.
struct DistanceLink {
  uint32_t a = 0;
  uint32_t b = 0;
  float rest = 0.0f;
  LinkKind kind = LinkKind::kEdge;
};

/// Every link of the sheet, colour after colour: colour c is
/// links[colour_starts[c], colour_starts[c + 1]).
struct ClothLinks {
  std::vector<DistanceLink> links;
  std::vector<uint32_t> colour_starts;  ///< colours + 1 entries
  uint32_t colours() const {
    return colour_starts.empty() ? 0 : static_cast<uint32_t>(colour_starts.size() - 1);
  }
};

/// Particles of a sheet at most (a 256 x 256 grid).
inline constexpr uint32_t kMaxClothParticles = 65536;

/// The links of a `columns` x `rows` sheet whose neighbours are `spacing`
/// metres apart. kInvalidArgument for fewer than 2 columns or rows, more
/// than kMaxClothParticles particles, or a spacing that is not a positive
/// finite number; `out` is then unchanged.
Status build_cloth_links(uint32_t columns, uint32_t rows, float spacing, ClothLinks& out);

}  // namespace rwd::sim::soft
