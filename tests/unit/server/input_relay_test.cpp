// SPDX-License-Identifier: MIT
// The relay of accepted inputs: runs of consecutive ticks per player, cut at
// gaps and at the packing limit, handed to every client but their player's,
// within the datagram's budget, and gone after the broadcast.
#include <gtest/gtest.h>

#include "rewind/core/stick_input.h"
#include "rewind/proto/input_packing.h"
#include "rewind/proto/message_inputs.h"
#include "rewind/server/input_relay.h"

namespace rwd::server {
namespace {

rwd::PlayerInput relayed_input_at(Tick t) {
  return rwd::stick_input(static_cast<int16_t>(t % 7 * 100), static_cast<int16_t>(-t % 5), 0);
}

std::vector<proto::RelayedRun> relayed_runs_for(const InputRelay& relay, uint32_t client,
                                                size_t budget = 1000) {
  v1::FinalTicks finals;
  finals.set_server_tick(500);
  relay.append_for(client, budget, 0, *finals.mutable_relayed());
  std::vector<proto::RelayedRun> runs;
  EXPECT_TRUE(proto::relayed_runs(finals, runs).ok());
  return runs;
}

TEST(InputRelay, AFrameBecomesRunsCutAtGapsAndGoesToEveryOtherClient) {
  InputRelay relay;
  relay.begin(1);
  for (Tick t : {10, 11, 12, 15, 16}) relay.add(t, relayed_input_at(t));
  EXPECT_EQ(relay.end(), 5u);
  relay.begin(0);
  relay.add(11, relayed_input_at(11));
  EXPECT_EQ(relay.end(), 1u);
  relay.pack(500);

  const std::vector<proto::RelayedRun> to_client2 = relayed_runs_for(relay, 2);
  ASSERT_EQ(to_client2.size(), 3u);
  EXPECT_EQ(to_client2[0].player, 1u);
  EXPECT_EQ(to_client2[0].first_tick, 10);
  ASSERT_EQ(to_client2[0].inputs.size(), 3u);
  EXPECT_EQ(to_client2[0].inputs[2], relayed_input_at(12));
  EXPECT_EQ(to_client2[1].first_tick, 15);
  EXPECT_EQ(to_client2[1].inputs.size(), 2u);
  EXPECT_EQ(to_client2[2].player, 0u);

  // A player never gets its own inputs back.
  const std::vector<proto::RelayedRun> to_client1 = relayed_runs_for(relay, 1);
  ASSERT_EQ(to_client1.size(), 1u);
  EXPECT_EQ(to_client1[0].player, 0u);
}

TEST(InputRelay, RunsStopAtThePackingLimit) {
  InputRelay relay;
  relay.begin(3);
  const Tick count = static_cast<Tick>(proto::kMaxPackedInputs) + 5;
  for (Tick t = 0; t < count; ++t) relay.add(100 + t, relayed_input_at(t));
  EXPECT_EQ(relay.end(), static_cast<size_t>(count));
  relay.pack(500);  // the server clock relayed_runs_for() decodes with
  const std::vector<proto::RelayedRun> runs = relayed_runs_for(relay, 0, 4000);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].inputs.size(), proto::kMaxPackedInputs);
  EXPECT_EQ(runs[1].first_tick, 100 + static_cast<Tick>(proto::kMaxPackedInputs));
  EXPECT_EQ(runs[1].inputs.size(), 5u);
}

TEST(InputRelay, RunsThatDoNotFitTheBudgetAreLeftOutAndTheRestKept) {
  InputRelay relay;
  for (uint32_t player = 0; player < 4; ++player) {
    relay.begin(player);
    for (Tick t = 0; t < 20; ++t) relay.add(t, relayed_input_at(t * (player + 3)));
    relay.end();
  }
  relay.pack(20);
  v1::FinalTicks all;
  const size_t left_all = relay.append_for(9, 10000, 0, *all.mutable_relayed());
  EXPECT_EQ(left_all, 10000 - all.relayed().size());
  // A budget for about two runs: the rest is skipped, and what is kept
  // never eats into the reserve.
  const size_t one_run = all.relayed().size() / 4;
  v1::FinalTicks some;
  const size_t keep = 100;
  const size_t left = relay.append_for(9, keep + 2 * one_run + 1, keep, *some.mutable_relayed());
  EXPECT_GE(left, keep);
  EXPECT_LT(some.relayed().size(), all.relayed().size());
  EXPECT_GT(some.relayed().size(), 0u);
  // A budget already inside the reserve takes nothing.
  v1::FinalTicks none;
  EXPECT_EQ(relay.append_for(9, keep - 1, keep, *none.mutable_relayed()), keep - 1);
  EXPECT_TRUE(none.relayed().empty());
}

TEST(InputRelay, ABroadcastEmptiesIt) {
  InputRelay relay;
  relay.begin(0);
  relay.add(5, relayed_input_at(5));
  relay.end();
  relay.pack(6);
  EXPECT_EQ(relay.runs(), 1u);
  relay.clear();
  EXPECT_EQ(relay.runs(), 0u);
  relay.pack(7);
  EXPECT_TRUE(relayed_runs_for(relay, 1).empty());
  // A frame with no accepted input relays nothing.
  relay.begin(2);
  EXPECT_EQ(relay.end(), 0u);
  EXPECT_EQ(relay.runs(), 0u);
}

}  // namespace
}  // namespace rwd::server
