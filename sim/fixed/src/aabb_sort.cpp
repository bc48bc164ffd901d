// SPDX-License-Identifier: MIT
#include "rewind/fixed/aabb_sort.h"

#include <algorithm>
#include <string>
#include <vector>

namespace rwd::fixed {

Status sort_by_stable_id(std::span<IdAabb2> items) {
  // Validate on a copy of the ids first so a refusal leaves items as given.
  std::vector<uint64_t> ids(items.size());
  for (size_t i = 0; i < items.size(); ++i) ids[i] = items[i].id;
  std::sort(ids.begin(), ids.end());
  const auto repeated = std::adjacent_find(ids.begin(), ids.end());
  if (repeated != ids.end()) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "aabb id " + std::to_string(*repeated) + " appears more than once");
  }
  // With unique keys the order is total, so any correct sort gives the same
  // result; stable_sort keeps that true even if the check above is relaxed.
  std::stable_sort(items.begin(), items.end(),
                   [](const IdAabb2& a, const IdAabb2& b) { return a.id < b.id; });
  return Status::Ok();
}

}  // namespace rwd::fixed
