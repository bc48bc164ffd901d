// SPDX-License-Identifier: MIT
// Packed inputs: lists and runs round-trip for any bytes, an unchanged
// input costs one byte, and every malformed list (cut short, trailing
// bytes, too many inputs, wrong reference count, a mask longer than the
// input) is kCorrupt. A delta final tick reads against the tick before
// it and is checked for its form where that is unknown.
#include <gtest/gtest.h>

#include <random>

#include "rewind/core/stick_input.h"
#include "rewind/proto/input_packing.h"
#include "rewind/proto/message_inputs.h"

namespace rwd::proto {
namespace {

using rwd::PlayerInput;

PlayerInput S(int16_t x, int16_t y, uint32_t buttons) {
  return rwd::stick_input(x, y, buttons);
}

// Any bytes: the packing does not know the game. Some inputs use all 32.
std::vector<PlayerInput> random_inputs(std::mt19937& rng, size_t n) {
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<PlayerInput> out;
  for (size_t i = 0; i < n; ++i) {
    PlayerInput in;
    const size_t used = i % 3 == 0 ? rwd::kInputCapacity : 8;
    for (size_t b = 0; b < used; ++b)
      in.bytes[b] = static_cast<uint8_t>(byte(rng) % 4 == 0 ? 0 : byte(rng));
    out.push_back(in);
  }
  return out;
}

TEST(InputPacking, ListsAndRunsRoundTrip) {
  std::mt19937 rng(5);
  for (size_t n : {size_t{0}, size_t{1}, size_t{8}, size_t{64}}) {
    const std::vector<PlayerInput> values = random_inputs(rng, n);
    const std::vector<PlayerInput> refs = random_inputs(rng, n);
    std::string bytes;
    pack_inputs(values, refs, bytes);
    std::vector<PlayerInput> back;
    ASSERT_TRUE(unpack_inputs(bytes, refs, back).ok());
    EXPECT_EQ(back, values);
    bytes.clear();
    pack_inputs(values, {}, bytes);
    ASSERT_TRUE(unpack_inputs(bytes, {}, back).ok());
    EXPECT_EQ(back, values);
    bytes.clear();
    pack_run(values, bytes);
    ASSERT_TRUE(unpack_run(bytes, back).ok());
    EXPECT_EQ(back, values);
  }
}

TEST(InputPacking, UnchangedInputsCostAByte) {
  const std::vector<PlayerInput> same(8, S(-707, 707, 2));
  std::string bytes;
  pack_inputs(same, same, bytes);
  EXPECT_EQ(bytes.size(), 1u + 8u);
  bytes.clear();
  pack_run(same, bytes);
  EXPECT_EQ(bytes.size(), 1u + (1u + 5u) + 7u);  // the first against neutral
}

TEST(InputPacking, MalformedListsAreCorrupt) {
  const std::vector<PlayerInput> values = {S(10, -20, 1), S(300, 0, 0)};
  std::string bytes;
  pack_inputs(values, {}, bytes);
  std::vector<PlayerInput> out;
  for (size_t cut = 0; cut < bytes.size(); ++cut) {
    EXPECT_EQ(unpack_inputs(bytes.substr(0, cut), {}, out).code(), ErrorCode::kCorrupt) << cut;
    EXPECT_TRUE(out.empty());
  }
  EXPECT_EQ(unpack_inputs(bytes + '\0', {}, out).code(), ErrorCode::kCorrupt);
  EXPECT_EQ(unpack_inputs(bytes, std::vector<PlayerInput>(3), out).code(), ErrorCode::kCorrupt);
  EXPECT_EQ(unpack_inputs(std::string(1, '\x41'), {}, out).code(), ErrorCode::kCorrupt);
  // A mask of more than 32 bits names bytes no input has.
  const std::string wide = {'\x01', '\x80', '\x80', '\x80', '\x80', '\x7F'};
  EXPECT_EQ(unpack_inputs(wide, {}, out).code(), ErrorCode::kCorrupt);
  EXPECT_EQ(unpack_run(wide, out).code(), ErrorCode::kCorrupt);
  EXPECT_EQ(check_packed_inputs(wide).code(), ErrorCode::kCorrupt);
  // Byte 31 changed: a five-byte mask, then the byte.
  PlayerInput last;
  last.bytes[31] = 9;
  bytes.clear();
  pack_inputs(std::vector<PlayerInput>{last}, {}, bytes);
  EXPECT_EQ(bytes.size(), 1u + 5u + 1u);
  ASSERT_TRUE(unpack_inputs(bytes, {}, out).ok());
  EXPECT_EQ(out, std::vector<PlayerInput>{last});
}

TEST(MessageInputs, ADeltaReadsAgainstTheTickBeforeAndIsCheckedForItsForm) {
  const std::vector<PlayerInput> a = {S(1, 2, 3), S(4, 5, 6)};
  const std::vector<PlayerInput> b = {S(1, 2, 3), S(-4, 5, 0)};
  v1::FinalTicks finals;
  v1::FinalTick* first = finals.add_ticks();
  first->set_tick(10);
  pack_inputs(a, {}, *first->mutable_packed_inputs());
  v1::FinalTick* second = finals.add_ticks();
  second->set_tick(11);
  pack_inputs(b, a, *second->mutable_packed_inputs());
  second->set_delta(true);
  EXPECT_TRUE(check_final_tick_inputs(finals).ok());
  std::vector<PlayerInput> out;
  ASSERT_TRUE(final_tick_inputs(*first, {}, out).ok());
  EXPECT_EQ(out, a);
  ASSERT_TRUE(final_tick_inputs(*second, a, out).ok());
  EXPECT_EQ(out, b);
  // Without the tick before, a delta cannot be read.
  EXPECT_EQ(final_tick_inputs(*second, {}, out).code(), ErrorCode::kCorrupt);
  // A delta cut short is refused by its form alone.
  second->mutable_packed_inputs()->pop_back();
  EXPECT_EQ(check_final_tick_inputs(finals).code(), ErrorCode::kCorrupt);
  // A standalone tick is read through, so a bad mask is refused.
  second->set_delta(false);
  first->set_packed_inputs(std::string{'\x01', '\x80', '\x80', '\x80', '\x80', '\x7F'});
  EXPECT_EQ(check_final_tick_inputs(finals).code(), ErrorCode::kCorrupt);
}

TEST(MessageInputs, RelayedRunsRoundTripAndRefuseBadBytes) {
  const std::vector<PlayerInput> a = {S(5, 5, 0), S(5, 6, 0)};
  const std::vector<PlayerInput> b = {S(-1000, 1000, 9)};
  v1::FinalTicks finals;
  finals.set_server_tick(1000);
  append_relayed_run(2, 1003, 1000, a, *finals.mutable_relayed());
  append_relayed_run(7, 990, 1000, b, *finals.mutable_relayed());
  std::vector<RelayedRun> runs;
  ASSERT_TRUE(relayed_runs(finals, runs).ok());
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].player, 2u);
  EXPECT_EQ(runs[0].first_tick, 1003);
  EXPECT_EQ(runs[0].inputs, a);
  EXPECT_EQ(runs[1].player, 7u);
  EXPECT_EQ(runs[1].first_tick, 990);
  EXPECT_EQ(runs[1].inputs, b);
  const std::string whole = finals.relayed();
  for (size_t cut = 1; cut < whole.size(); ++cut) {
    finals.set_relayed(whole.substr(0, cut));
    // Every prefix ends on a run boundary (then it holds the first run)
    // or is refused; none is read as something else.
    const Status s = relayed_runs(finals, runs);
    if (s.ok()) {
      EXPECT_EQ(runs.size(), 1u) << cut;
    } else {
      EXPECT_EQ(s.code(), ErrorCode::kCorrupt);
      EXPECT_TRUE(runs.empty());
    }
  }
  finals.set_relayed(std::string(1, '\x40'));  // player 64
  EXPECT_FALSE(relayed_runs(finals, runs).ok());
  finals.set_server_tick(0);
  finals.clear_relayed();
  append_relayed_run(1, 0, 5, a, *finals.mutable_relayed());  // tick -5
  EXPECT_FALSE(relayed_runs(finals, runs).ok());
}

}  // namespace
}  // namespace rwd::proto
