// SPDX-License-Identifier: MIT
// Live tick batches: every field round-trips; every truncation and every
// bad field is refused with a message naming it; an inconsistent batch is
// not written.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rewind/core/stick_input.h"
#include "rewind/viewer/live_ticks.h"

namespace rwd::viewer {
namespace {

LiveTicks sample() {
  LiveTicks b;
  b.player_count = 2;
  b.player_names = {"ada", ""};
  b.newest_final = 907;
  b.ended = true;
  b.first_tick = 900;
  for (uint32_t t = 0; t < 4; ++t) {
    b.checksums.push_back(0xABCD0000ull + t);
    b.substituted_masks.push_back(t == 2 ? 2 : 0);
    for (uint32_t p = 0; p < 2; ++p) {
      b.inputs.push_back(rwd::stick_input(static_cast<int16_t>(-1000 + 300 * static_cast<int>(t)),
                                          static_cast<int16_t>(p * 10), 0xF0u >> p));
    }
  }
  return b;
}

void expect_same(const LiveTicks& a, const LiveTicks& b) {
  EXPECT_EQ(a.player_count, b.player_count);
  EXPECT_EQ(a.player_names, b.player_names);
  EXPECT_EQ(a.newest_final, b.newest_final);
  EXPECT_EQ(a.ended, b.ended);
  EXPECT_EQ(a.first_tick, b.first_tick);
  EXPECT_EQ(a.checksums, b.checksums);
  EXPECT_EQ(a.substituted_masks, b.substituted_masks);
  EXPECT_EQ(a.inputs, b.inputs);
}

TEST(LiveTicks, RoundTripsEveryField) {
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(encode_live_ticks(sample(), bytes).ok());
  auto back = decode_live_ticks(bytes);
  ASSERT_TRUE(back.ok()) << back.status().message();
  expect_same(sample(), *back);

  LiveTicks empty = sample();  // nothing new yet: no ticks, no names
  empty.player_names.clear();
  empty.checksums.clear();
  empty.substituted_masks.clear();
  empty.inputs.clear();
  empty.newest_final = kNoTick;
  empty.ended = false;
  ASSERT_TRUE(encode_live_ticks(empty, bytes).ok());
  back = decode_live_ticks(bytes);
  ASSERT_TRUE(back.ok()) << back.status().message();
  expect_same(empty, *back);
}

TEST(LiveTicks, EveryTruncationAndBadFieldIsRefused) {
  std::vector<uint8_t> good;
  ASSERT_TRUE(encode_live_ticks(sample(), good).ok());
  for (size_t n = 0; n < good.size(); ++n) {
    auto cut = decode_live_ticks(std::span<const uint8_t>(good).first(n));
    ASSERT_FALSE(cut.ok()) << n;
    EXPECT_EQ(cut.status().code(), ErrorCode::kCorrupt);
  }
  std::vector<uint8_t> longer = good;
  longer.push_back(0);
  auto left_over = decode_live_ticks(longer);
  ASSERT_FALSE(left_over.ok());
  EXPECT_NE(left_over.status().message().find("left over"), std::string::npos);

  auto refused = [&](size_t offset, uint8_t value, const char* named) {
    std::vector<uint8_t> bytes = good;
    bytes[offset] = value;
    auto r = decode_live_ticks(bytes);
    ASSERT_FALSE(r.ok()) << offset;
    EXPECT_NE(r.status().message().find(named), std::string::npos) << r.status().message();
  };
  refused(0, 'X', "magic");
  refused(8, 1, "version");
  refused(8, 3, "version");
  refused(12, 0, "player count");  // after magic (8) and version (4)
  refused(12, 33, "player count");
  refused(16, 1, "name count");  // neither 0 nor 2
  // Names "ada" (4 + 3) and "" (4): newest final at 31, ended at 35.
  refused(35, 2, "ended flag");
  refused(34, 0xFF, "newest final");  // 907 | 0xFF000000: below -1
  refused(39, 0x80, "first tick");    // negative
}

TEST(LiveTicks, InconsistentBatchesAreNotWritten) {
  std::vector<uint8_t> out = {7};
  LiveTicks b = sample();
  b.inputs.pop_back();
  EXPECT_FALSE(encode_live_ticks(b, out).ok());
  b = sample();
  b.player_names.pop_back();
  EXPECT_FALSE(encode_live_ticks(b, out).ok());
  b = sample();
  b.first_tick = -2;
  EXPECT_FALSE(encode_live_ticks(b, out).ok());
  b = sample();
  b.player_count = 0;
  EXPECT_FALSE(encode_live_ticks(b, out).ok());
  EXPECT_EQ(out, std::vector<uint8_t>{7});
}

}  // namespace
}  // namespace rwd::viewer
