// SPDX-License-Identifier: MIT
// Replay summaries (inspect) and the rewrite behind `rewind-replay tamper`.
#include "replay_io_support.h"

namespace rwd::replay {
namespace {

using namespace io_test;  // NOLINT: test helpers

TEST(ReplayIo, SummaryCountsRecordsAndSubstitutions) {
  TempFile file("summary");
  write_small_replay(file.path(), 6);
  Result<ReplaySummary> s = summarize_replay(file.path());
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->header.game(), "crates");
  EXPECT_EQ(s->tick_records, 6u);
  EXPECT_EQ(s->first_tick, 0);
  EXPECT_EQ(s->last_tick, 5);
  EXPECT_EQ(s->substituted_per_player, (std::vector<uint64_t>{1, 0, 1}));
  EXPECT_EQ(s->ticks_with_substitutions, 1u);
  ASSERT_EQ(s->keyframes.size(), 2u);
  EXPECT_EQ(s->keyframes[1].tick, 3);
  EXPECT_EQ(s->keyframes[1].state_bytes, 17u);
  ASSERT_TRUE(s->end.has_value());
  EXPECT_EQ(s->end->reason(), "match over");
  EXPECT_FALSE(s->error.has_value());
  EXPECT_EQ(s->state, ReadState::kComplete);
  EXPECT_EQ(s->valid_bytes, file_size(file.path()));
  EXPECT_EQ(s->header.sim_revision(), 2u);

  std::vector<uint8_t> bytes = read_all(file.path());
  bytes.resize(bytes.size() - 3);
  write_all(file.path(), bytes);
  s = summarize_replay(file.path());
  ASSERT_TRUE(s.ok());
  ASSERT_TRUE(s->error.has_value());
  EXPECT_NE(s->error->find("truncated frame"), std::string::npos);
  EXPECT_EQ(s->state, ReadState::kTorn);
  EXPECT_FALSE(s->end.has_value());
  EXPECT_EQ(s->last_tick, 5);

  // Cut on the boundary before the end record: no error, but incomplete.
  fs::remove(file.path());
  const std::vector<uint64_t> starts = write_small_replay(file.path(), 6);
  bytes = read_all(file.path());
  bytes.resize(starts[starts.size() - 2]);
  write_all(file.path(), bytes);
  s = summarize_replay(file.path());
  ASSERT_TRUE(s.ok());
  EXPECT_FALSE(s->error.has_value());
  EXPECT_EQ(s->state, ReadState::kIncomplete);
  EXPECT_EQ(s->last_tick, 5);

  // A flipped bit inside a frame is corruption.
  bytes[starts[3] + kFrameHeaderBytes + 1] ^= 0x04;
  write_all(file.path(), bytes);
  s = summarize_replay(file.path());
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->state, ReadState::kCorrupt);
}

TEST(ReplayIo, RewriteForgesOneInputWithValidFraming) {
  TempFile in("rewrite_in");
  TempFile out("rewrite_out");
  write_small_replay(in.path(), 6);
  InputEdit edit;
  edit.tick = 3;
  edit.player = 1;
  edit.fields = {{"axis_x", -999}};
  Result<InputRewrite> original =
      rewrite_replay_input(in.path(), out.path(), edit, rwd::stick_input_spec(), false);
  ASSERT_TRUE(original.ok()) << original.status().message();
  EXPECT_EQ(original->before, inputs_for(3, 3)[1]);
  const rwd::StickInput before = original->before.as<rwd::StickInput>();
  EXPECT_EQ(original->after, rwd::stick_input(-999, before.axis_y, before.buttons));
  EXPECT_EQ(original->after_text, "axis_x=-999 axis_y=" + std::to_string(before.axis_y) +
                                      " buttons=" + std::to_string(before.buttons));

  Result<ReplayReader> a = ReplayReader::open(in.path());
  Result<ReplayReader> b = ReplayReader::open(out.path());
  ASSERT_TRUE(a.ok() && b.ok());
  std::vector<v1::ReplayRecord> ra;
  std::vector<v1::ReplayRecord> rb;
  ASSERT_EQ(drain(*a, &ra), "");
  ASSERT_EQ(drain(*b, &rb), "");  // every frame hash is valid
  ASSERT_EQ(ra.size(), rb.size());
  int changed = 0;
  for (size_t i = 0; i < ra.size(); ++i) {
    if (ra[i].SerializeAsString() == rb[i].SerializeAsString()) continue;
    ++changed;
    ASSERT_TRUE(rb[i].has_tick());
    EXPECT_EQ(rb[i].tick().tick(), 3);
    const auto forged = proto::from_wire(rb[i].tick().inputs(1))->as<rwd::StickInput>();
    const auto recorded = proto::from_wire(ra[i].tick().inputs(1))->as<rwd::StickInput>();
    EXPECT_EQ(forged.axis_x, -999);
    EXPECT_EQ(forged.axis_y, recorded.axis_y);
    EXPECT_EQ(rb[i].tick().checksum(), ra[i].tick().checksum());
  }
  EXPECT_EQ(changed, 1);
  EXPECT_TRUE(b->ended());

  // Refusals: existing output, missing tick, missing player.
  EXPECT_FALSE(
      rewrite_replay_input(in.path(), out.path(), edit, rwd::stick_input_spec(), false).ok());
  EXPECT_TRUE(
      rewrite_replay_input(in.path(), out.path(), edit, rwd::stick_input_spec(), true).ok());
  edit.tick = 60;
  EXPECT_EQ(rewrite_replay_input(in.path(), out.path(), edit, rwd::stick_input_spec(), true)
                .status()
                .code(),
            ErrorCode::kNotFound);
  EXPECT_FALSE(fs::exists(out.path()));  // no half-forged file left behind
  edit.tick = 1;
  edit.player = 3;
  EXPECT_EQ(rewrite_replay_input(in.path(), out.path(), edit, rwd::stick_input_spec(), true)
                .status()
                .code(),
            ErrorCode::kInvalidArgument);
  edit.player = 0;
  EXPECT_FALSE(
      rewrite_replay_input(in.path(), in.path(), edit, rwd::stick_input_spec(), true).ok());
  // Fields are the game's: an unknown one, or a value outside its range.
  edit.fields = {{"throttle", 1}};
  Result<InputRewrite> unknown =
      rewrite_replay_input(in.path(), out.path(), edit, rwd::stick_input_spec(), true);
  EXPECT_EQ(unknown.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(unknown.status().message(),
            "the input ('stick') has no field 'throttle' (fields: axis_x, axis_y, buttons)");
  edit.fields = {{"axis_y", 1001}};
  EXPECT_EQ(rewrite_replay_input(in.path(), out.path(), edit, rwd::stick_input_spec(), true)
                .status()
                .message(),
            "input field 'axis_y' = 1001 is outside [-1000, 1000]");
  EXPECT_TRUE(ReplayReader::open(in.path()).ok());  // input untouched
}

}  // namespace
}  // namespace rwd::replay
