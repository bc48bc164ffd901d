// SPDX-License-Identifier: MIT
#include "rewind/fixed/aabb_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "splitmix.h"

namespace rwd::fixed {
namespace {

IdAabb2 item(uint64_t id, int32_t x) {
  return {id, *Aabb2::make(Vec2(Fx(x), Fx(0)), Vec2(Fx(x + 1), Fx(1)))};
}

TEST(FixedSortByStableId, OrdersByIdWhateverTheInputOrder) {
  std::vector<IdAabb2> sorted;
  for (uint64_t id = 0; id < 200; ++id)
    sorted.push_back(item(id * 7 + 3, static_cast<int32_t>(id)));
  SplitMix64 rng{51};
  for (int round = 0; round < 20; ++round) {
    std::vector<IdAabb2> shuffled = sorted;
    for (size_t i = shuffled.size() - 1; i > 0; --i)
      std::swap(shuffled[i], shuffled[rng.below(static_cast<uint32_t>(i + 1))]);
    ASSERT_TRUE(sort_by_stable_id(shuffled).ok());
    ASSERT_EQ(shuffled, sorted);
  }
  std::vector<IdAabb2> empty;
  EXPECT_TRUE(sort_by_stable_id(empty).ok());
}

TEST(FixedSortByStableId, RefusesRepeatedIdsAndLeavesTheInput) {
  std::vector<IdAabb2> items = {item(9, 0), item(4, 1), item(9, 2), item(1, 3)};
  const std::vector<IdAabb2> before = items;
  const Status status = sort_by_stable_id(items);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(status.message().find("9"), std::string::npos);
  EXPECT_EQ(items, before);
}

}  // namespace
}  // namespace rwd::fixed
