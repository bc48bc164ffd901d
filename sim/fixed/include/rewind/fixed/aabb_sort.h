// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <span>

#include "rewind/core/status.h"
#include "rewind/fixed/aabb2.h"

namespace rwd::fixed {

/// A box tagged with the stable id of what it bounds.
struct IdAabb2 {
  uint64_t id = 0;
  Aabb2 box;
  friend constexpr bool operator==(IdAabb2 a, IdAabb2 b) = default;
};

/// Orders `items` by ascending id, so pairwise checks that walk the result
/// visit pairs in the same order on every machine, whatever order the boxes
/// were gathered in. Ids must be unique: a repeated id is refused with
/// kInvalidArgument naming it, and `items` is then left untouched.
/// `items` is used only during the call. Allocates a scratch copy of the ids
/// (O(n) memory); O(n log n) time.
Status sort_by_stable_id(std::span<IdAabb2> items);

}  // namespace rwd::fixed
