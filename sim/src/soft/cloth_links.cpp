// SPDX-License-Identifier: MIT
#include "soft/cloth_links.h"

#include <cmath>
#include <string>

namespace rwd::sim::soft {
namespace {

// One family of links: from (column, row) to (column + dc, row + dr) for
// every start where both ends are on the sheet, split into colours by the
// start's position modulo (period_c, period_r). Two links of one colour
// start period apart, which is farther than the link reaches, so they share
// no particle.
void add_family(uint32_t columns, uint32_t rows, int dc, int dr, uint32_t period_c,
                uint32_t period_r, float rest, LinkKind kind, ClothLinks& out) {
  for (uint32_t pr = 0; pr < period_r; ++pr) {
    for (uint32_t pc = 0; pc < period_c; ++pc) {
      for (uint32_t r = pr; r < rows; r += period_r) {
        for (uint32_t c = pc; c < columns; c += period_c) {
          const int64_t c2 = int64_t{c} + dc;
          const int64_t r2 = int64_t{r} + dr;
          if (c2 < 0 || r2 < 0 || c2 >= columns || r2 >= rows) continue;
          out.links.push_back({r * columns + c,
                               static_cast<uint32_t>(r2) * columns + static_cast<uint32_t>(c2),
                               rest, kind});
        }
      }
      out.colour_starts.push_back(static_cast<uint32_t>(out.links.size()));
    }
  }
}

}  // namespace

Status build_cloth_links(uint32_t columns, uint32_t rows, float spacing, ClothLinks& out) {
  if (columns < 2 || rows < 2) {
    return Status::Error(ErrorCode::kInvalidArgument, "cloth: at least 2 columns and 2 rows (got " +
                                                          std::to_string(columns) + " x " +
                                                          std::to_string(rows) + ")");
  }
  if (uint64_t{columns} * rows > kMaxClothParticles) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "cloth: " + std::to_string(uint64_t{columns} * rows) +
                             " particles, more than " + std::to_string(kMaxClothParticles));
  }
  if (!std::isfinite(spacing) || !(spacing > 0.0f)) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "cloth: spacing must be a positive finite number of metres");
  }
  ClothLinks links;
  links.colour_starts.push_back(0);
  const float diagonal = spacing * std::sqrt(2.0f);
  add_family(columns, rows, 1, 0, 2, 1, spacing, LinkKind::kEdge, links);     // along rows
  add_family(columns, rows, 0, 1, 1, 2, spacing, LinkKind::kEdge, links);     // along columns
  add_family(columns, rows, 1, 1, 2, 2, diagonal, LinkKind::kShear, links);   // one diagonal
  add_family(columns, rows, -1, 1, 2, 2, diagonal, LinkKind::kShear, links);  // the other
  add_family(columns, rows, 2, 0, 4, 1, 2.0f * spacing, LinkKind::kBend, links);
  add_family(columns, rows, 0, 2, 1, 4, 2.0f * spacing, LinkKind::kBend, links);
  out = std::move(links);
  return Status::Ok();
}

}  // namespace rwd::sim::soft
