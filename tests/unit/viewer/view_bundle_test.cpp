// SPDX-License-Identifier: MIT
// View bundles: every field round-trips; every truncation and every bad
// field is refused with a message naming it.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "rewind/core/stick_input.h"
#include "rewind/viewer/view_bundle.h"

namespace rwd::viewer {
namespace {

ViewBundle sample() {
  ViewBundle b;
  b.game = "crates";
  b.setup.player_count = 3;
  b.setup.seed = 0x1122334455667788ull;
  b.tick_rate_hz = 30;
  b.identity_matches = false;
  b.identity_note = "sim revision: recorded 19, this build 20";
  b.player_names = {"ada", "bo", ""};
  for (uint32_t t = 0; t < 5; ++t) {
    for (uint32_t p = 0; p < 3; ++p) {
      b.inputs.push_back(
          rwd::stick_input(static_cast<int16_t>(-1000 + 37 * static_cast<int>(t + p)),
                           static_cast<int16_t>(999 - static_cast<int>(p)), 0x80000001u >> p));
    }
    b.checksums.push_back(0xF00D0000ull + t);
    b.substituted_masks.push_back(t % 2 == 0 ? 0 : 5);
  }
  b.desync = ViewDesync{3, 2, "player 2 desync at tick 3", {1, 2, 3, 250}};
  return b;
}

void expect_same(const ViewBundle& a, const ViewBundle& b) {
  EXPECT_EQ(a.game, b.game);
  EXPECT_EQ(a.setup.player_count, b.setup.player_count);
  EXPECT_EQ(a.setup.seed, b.setup.seed);
  EXPECT_EQ(a.tick_rate_hz, b.tick_rate_hz);
  EXPECT_EQ(a.identity_matches, b.identity_matches);
  EXPECT_EQ(a.identity_note, b.identity_note);
  EXPECT_EQ(a.player_names, b.player_names);
  EXPECT_EQ(a.first_tick, b.first_tick);
  EXPECT_EQ(a.start_state, b.start_state);
  ASSERT_EQ(a.keyframes.size(), b.keyframes.size());
  for (size_t k = 0; k < a.keyframes.size(); ++k) {
    EXPECT_EQ(a.keyframes[k].position, b.keyframes[k].position);
    EXPECT_EQ(a.keyframes[k].state, b.keyframes[k].state);
  }
  EXPECT_EQ(a.inputs, b.inputs);
  EXPECT_EQ(a.checksums, b.checksums);
  EXPECT_EQ(a.substituted_masks, b.substituted_masks);
  ASSERT_EQ(a.desync.has_value(), b.desync.has_value());
  if (a.desync) {
    EXPECT_EQ(a.desync->tick, b.desync->tick);
    EXPECT_EQ(a.desync->player, b.desync->player);
    EXPECT_EQ(a.desync->headline, b.desync->headline);
    EXPECT_EQ(a.desync->client_state, b.desync->client_state);
  }
}

TEST(ViewBundle, RoundTripsEveryField) {
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(encode_view_bundle(sample(), bytes).ok());
  auto back = decode_view_bundle(bytes);
  ASSERT_TRUE(back.ok()) << back.status().message();
  expect_same(sample(), *back);

  ViewBundle bare = sample();
  bare.player_names.clear();
  bare.desync.reset();
  ASSERT_TRUE(encode_view_bundle(bare, bytes).ok());
  back = decode_view_bundle(bytes);
  ASSERT_TRUE(back.ok()) << back.status().message();
  expect_same(bare, *back);
}

TEST(ViewBundle, ALaterStartRoundTripsWithItsState) {
  ViewBundle later = sample();
  later.first_tick = 4000;
  later.start_state = {9, 8, 7, 6, 5};
  EXPECT_EQ(later.end_position(), 4005);
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(encode_view_bundle(later, bytes).ok());
  auto back = decode_view_bundle(bytes);
  ASSERT_TRUE(back.ok()) << back.status().message();
  expect_same(later, *back);

  // A later start without the state before it cannot be played.
  later.start_state.clear();
  std::vector<uint8_t> untouched = {1};
  EXPECT_EQ(encode_view_bundle(later, untouched).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(untouched, std::vector<uint8_t>{1});
  later.first_tick = -1;
  EXPECT_EQ(encode_view_bundle(later, untouched).code(), ErrorCode::kInvalidArgument);
}

TEST(ViewBundle, KeyframesRoundTripAndMustAscendWithinTheTicks) {
  ViewBundle b = sample();
  b.first_tick = 10;
  b.start_state = {1};
  b.keyframes = {{12, {4, 5}}, {15, {6}}};  // the ticks run 10..14: positions up to 15
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(encode_view_bundle(b, bytes).ok());
  auto back = decode_view_bundle(bytes);
  ASSERT_TRUE(back.ok()) << back.status().message();
  expect_same(b, *back);

  std::vector<uint8_t> untouched = {3};
  for (const std::vector<ViewKeyframe>& bad :
       {std::vector<ViewKeyframe>{{10, {1}}},             // not after the first tick
        std::vector<ViewKeyframe>{{16, {1}}},             // past the ticks
        std::vector<ViewKeyframe>{{13, {1}}, {12, {1}}},  // descending
        std::vector<ViewKeyframe>{{13, {}}}}) {           // no state
    ViewBundle refused = b;
    refused.keyframes = bad;
    EXPECT_EQ(encode_view_bundle(refused, untouched).code(), ErrorCode::kInvalidArgument);
  }
  EXPECT_EQ(untouched, std::vector<uint8_t>{3});
}

TEST(ViewBundle, VersionOneAndTwoBundlesStillLoad) {
  // Versions 1 and 2 stored each input as the stick's 8 bytes, where
  // version 3 stores a length and the bytes without trailing zeros (here
  // all 8 are used: 9 bytes). Version 1 also had no first tick, start state
  // or keyframes: 12 bytes fewer before the ticks.
  const ViewBundle old = sample();
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(encode_view_bundle(old, bytes).ok());
  constexpr size_t kDesync = 1 + 4 + 4 + 4 + 25 + 4 + 4;
  constexpr size_t kTicks = 4 + 5 * (16 + 3 * 9);
  const size_t ticks_at = bytes.size() - kDesync - kTicks;
  std::vector<uint8_t> stick_ticks(bytes.begin() + static_cast<ptrdiff_t>(ticks_at),
                                   bytes.begin() + static_cast<ptrdiff_t>(ticks_at) + 4);
  size_t at = ticks_at + 4;
  for (int t = 0; t < 5; ++t) {
    stick_ticks.insert(stick_ticks.end(), bytes.begin() + static_cast<ptrdiff_t>(at),
                       bytes.begin() + static_cast<ptrdiff_t>(at) + 16);
    at += 16;
    for (int p = 0; p < 3; ++p) {
      ASSERT_EQ(bytes[at], 8u);
      stick_ticks.insert(stick_ticks.end(), bytes.begin() + static_cast<ptrdiff_t>(at) + 1,
                         bytes.begin() + static_cast<ptrdiff_t>(at) + 9);
      at += 9;
    }
  }
  for (const uint32_t version : {1u, 2u}) {
    const size_t head = ticks_at - (version == 1 ? 12 : 0);
    std::vector<uint8_t> older(bytes.begin(), bytes.begin() + static_cast<ptrdiff_t>(head));
    older.insert(older.end(), stick_ticks.begin(), stick_ticks.end());
    older.insert(older.end(), bytes.end() - static_cast<ptrdiff_t>(kDesync), bytes.end());
    older[8] = static_cast<uint8_t>(version);
    auto back = decode_view_bundle(older);
    ASSERT_TRUE(back.ok()) << version << ": " << back.status().message();
    expect_same(old, *back);
    EXPECT_EQ(back->first_tick, 0);
  }
}

TEST(ViewBundle, EveryTruncationIsRefused) {
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(encode_view_bundle(sample(), bytes).ok());
  for (size_t n = 0; n < bytes.size(); ++n) {
    auto cut = decode_view_bundle(std::span<const uint8_t>(bytes).first(n));
    ASSERT_FALSE(cut.ok()) << n;
    EXPECT_EQ(cut.status().code(), ErrorCode::kCorrupt);
  }
  bytes.push_back(0);
  auto longer = decode_view_bundle(bytes);
  ASSERT_FALSE(longer.ok());
  EXPECT_NE(longer.status().message().find("left over"), std::string::npos);
}

TEST(ViewBundle, BadFieldsAreNamed) {
  std::vector<uint8_t> good;
  ASSERT_TRUE(encode_view_bundle(sample(), good).ok());
  auto refused = [&](size_t offset, uint8_t value, const char* named) {
    std::vector<uint8_t> bytes = good;
    bytes[offset] = value;
    auto r = decode_view_bundle(bytes);
    ASSERT_FALSE(r.ok()) << offset;
    EXPECT_NE(r.status().message().find(named), std::string::npos) << r.status().message();
  };
  refused(0, 'X', "magic");
  refused(8, 4, "version");
  refused(8, 0, "version");
  // 8 magic + 4 version + 4 + 6 "crates": the player count.
  refused(22, 0, "player count");
  refused(22, 33, "player count");
  refused(38, 2, "identity flag");  // after the seed (8) and the tick rate (4)
  // An input longer than 32 bytes: a full input's length byte, found by
  // its 32 bytes of 0xEE, raised to 33.
  ViewBundle full = sample();
  full.inputs[0].bytes.fill(0xEE);
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(encode_view_bundle(full, bytes).ok());
  const std::vector<uint8_t> run(32, 0xEE);
  auto found = std::search(bytes.begin(), bytes.end(), run.begin(), run.end());
  ASSERT_NE(found, bytes.end());
  ASSERT_EQ(*(found - 1), 32u);
  *(found - 1) = 33;
  auto r = decode_view_bundle(bytes);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("input length"), std::string::npos) << r.status().message();
}

TEST(ViewBundle, InconsistentBundlesAreNotWritten) {
  std::vector<uint8_t> out = {42};
  ViewBundle b = sample();
  b.inputs.pop_back();
  EXPECT_FALSE(encode_view_bundle(b, out).ok());
  b = sample();
  b.player_names.pop_back();
  EXPECT_FALSE(encode_view_bundle(b, out).ok());
  b = sample();
  b.setup.player_count = 0;
  EXPECT_FALSE(encode_view_bundle(b, out).ok());
  EXPECT_EQ(out, std::vector<uint8_t>{42});  // untouched
}

}  // namespace
}  // namespace rwd::viewer
