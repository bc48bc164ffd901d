// SPDX-License-Identifier: MIT
#include "rewind/core/state_hasher.h"

#include <gtest/gtest.h>

namespace rwd {
namespace {

struct SomeId {
  uint32_t index = 0;
  uint32_t generation = 0;
};

uint64_t digest_of_id(SomeId id) {
  StateHasher h;
  h.add_id(id);
  return h.digest();
}

TEST(StateHasher, AnIdIsItsIndexThenItsGeneration) {
  StateHasher by_hand;
  by_hand.add_u32(7);
  by_hand.add_u32(3);
  EXPECT_EQ(digest_of_id({7, 3}), by_hand.digest());
  // A recycled slot (same index, new generation) hashes differently.
  EXPECT_NE(digest_of_id({7, 3}), digest_of_id({7, 4}));
}

TEST(StateHasher, MinusZeroHashesAsZero) {
  StateHasher a;
  a.add_f32(-0.0f);
  StateHasher b;
  b.add_f32(0.0f);
  EXPECT_EQ(a.digest(), b.digest());
}

}  // namespace
}  // namespace rwd
