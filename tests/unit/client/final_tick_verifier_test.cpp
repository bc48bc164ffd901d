// SPDX-License-Identifier: MIT
// FinalTickVerifier on a bare RollbackSession: final ticks applied in order
// whatever order they arrive in (a packed tick against the one applied
// before it), each checked once simulated, and a checksum that differs
// reported as a mismatch instead of agreed.
#include "final_tick_verifier.h"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <vector>

#include "rewind/core/stick_input.h"
#include "rewind/game/simulation.h"
#include "rewind/proto/input_packing.h"
#include "rewind/proto/input_wire.h"

namespace rwd::client {
namespace {

constexpr uint32_t kVerifierPlayers = 2;
constexpr int32_t kVerifierSnapshotTicks = 64;
constexpr uint32_t kOurSlot = 0;

std::unique_ptr<game::Simulation> verifier_match() {
  auto sim = game::Simulation::create("crates", {kVerifierPlayers, 7});
  if (!sim.ok()) throw std::runtime_error(sim.status().message());
  return std::move(*sim);
}

rwd::PlayerInput true_input(uint32_t player, Tick tick) {
  return rwd::stick_input(static_cast<int16_t>((tick * 53 + player * 400) % 2001 - 1000),
                          static_cast<int16_t>(player * 100 - tick % 3));
}

// The server's side: every tick's true inputs and the checksum after it,
// and its final ticks as the server sends them.
struct Authority {
  std::unique_ptr<game::Simulation> sim = verifier_match();
  std::vector<std::vector<rwd::PlayerInput>> inputs;
  std::vector<uint64_t> checksums;

  explicit Authority(Tick through) {
    while (sim->tick() <= through) {
      std::vector<rwd::PlayerInput> row;
      for (uint32_t p = 0; p < kVerifierPlayers; ++p) row.push_back(true_input(p, sim->tick()));
      if (!sim->step(row).ok()) throw std::runtime_error("authority step failed");
      inputs.push_back(std::move(row));
      checksums.push_back(sim->checksum());
    }
  }
  v1::FinalTick standalone(Tick t) const {
    v1::FinalTick out;
    out.set_tick(t);
    for (const rwd::PlayerInput& input : inputs.at(t)) *out.add_inputs() = proto::to_wire(input);
    out.set_checksum(checksums.at(t));
    return out;
  }
  /// Packed against tick t - 1's inputs, as the server sends a tick that
  /// follows the one before in the same stream.
  v1::FinalTick packed(Tick t) const {
    v1::FinalTick out;
    out.set_tick(t);
    proto::pack_inputs(inputs.at(t), inputs.at(t - 1), *out.mutable_packed_inputs());
    out.set_delta(true);
    out.set_checksum(checksums.at(t));
    return out;
  }
};

v1::FinalTicks message(std::vector<v1::FinalTick> ticks) {
  v1::FinalTicks out;
  for (v1::FinalTick& tick : ticks) *out.add_ticks() = std::move(tick);
  return out;
}

struct VerifierRig {
  std::unique_ptr<net::RollbackSession> session;
  FinalTickVerifier verifier{kVerifierSnapshotTicks};

  VerifierRig() {
    net::RollbackConfig config;
    config.snapshot_ticks = kVerifierSnapshotTicks;
    config.input_ticks = kVerifierSnapshotTicks + 256;
    session = std::make_unique<net::RollbackSession>(verifier_match(), config);
    verifier.seat(kOurSlot, kVerifierPlayers);
  }
  /// Simulates through `tick` with our own true inputs and whatever the
  /// session knows (or predicts) of the other player's, as the client does.
  void simulate_through(Tick tick) {
    while (session->current_tick() <= tick) {
      const Tick t = session->current_tick();
      (void)session->add_input(kOurSlot, t, true_input(kOurSlot, t));
      ASSERT_TRUE(session->advance());
    }
  }
};

TEST(FinalTickVerifier, AppliesFinalTicksInOrderWhateverOrderTheyArriveIn) {
  const Authority server(5);
  VerifierRig rig;
  // Ticks 2..4 arrive ahead of a gap (3 and 4 packed against the tick
  // before): held back, nothing applied.
  EXPECT_EQ(rig.verifier.apply(*rig.session,
                               message({server.standalone(2), server.packed(3), server.packed(4)})),
            FinalTickVerifier::Applied::kOk);
  EXPECT_EQ(rig.verifier.last_received(), kNoTick);
  EXPECT_EQ(rig.verifier.held_back(), 3u);
  EXPECT_EQ(rig.verifier.pending(), 0u);

  // The gap closes: 0 and 1, then the held ticks follow, tick 3 unpacked
  // against tick 2's inputs.
  EXPECT_EQ(rig.verifier.apply(*rig.session, message({server.standalone(0), server.packed(1)})),
            FinalTickVerifier::Applied::kOk);
  EXPECT_EQ(rig.verifier.last_received(), 4);
  EXPECT_EQ(rig.verifier.held_back(), 0u);
  EXPECT_EQ(rig.verifier.pending(), 5u);

  // Resends of applied ticks are duplicates.
  EXPECT_EQ(rig.verifier.apply(*rig.session, message({server.standalone(1), server.packed(2)})),
            FinalTickVerifier::Applied::kOk);
  EXPECT_EQ(rig.verifier.pending(), 5u);

  // Nothing is checked before it is simulated.
  EXPECT_EQ(rig.verifier.check_next(*rig.session).verdict, FinalTickVerifier::Verdict::kNone);
  rig.simulate_through(4);
  for (Tick t = 0; t <= 4; ++t) {
    const FinalTickVerifier::Check check = rig.verifier.check_next(*rig.session);
    EXPECT_EQ(check.verdict, FinalTickVerifier::Verdict::kAgreed) << "tick " << t;
    EXPECT_EQ(check.tick, t);
    EXPECT_EQ(check.local_checksum, server.checksums[t]);
    EXPECT_EQ(check.server_checksum, server.checksums[t]);
  }
  EXPECT_EQ(rig.verifier.check_next(*rig.session).verdict, FinalTickVerifier::Verdict::kNone);
  EXPECT_EQ(rig.verifier.agreed_through(), 4);
}

TEST(FinalTickVerifier, ReportsAChecksumThatDiffersAsAMismatch) {
  const Authority server(3);
  VerifierRig rig;
  // Simulated first on predictions of the other player: the final inputs
  // roll the session back, and only tick 2's checksum is wrong.
  rig.simulate_through(3);
  v1::FinalTicks finals =
      message({server.standalone(0), server.packed(1), server.packed(2), server.packed(3)});
  const uint64_t wrong = server.checksums[2] ^ 0x5A5A;
  finals.mutable_ticks(2)->set_checksum(wrong);
  EXPECT_EQ(rig.verifier.apply(*rig.session, finals), FinalTickVerifier::Applied::kOk);

  EXPECT_EQ(rig.verifier.check_next(*rig.session).verdict, FinalTickVerifier::Verdict::kAgreed);
  EXPECT_EQ(rig.verifier.check_next(*rig.session).verdict, FinalTickVerifier::Verdict::kAgreed);
  const FinalTickVerifier::Check mismatch = rig.verifier.check_next(*rig.session);
  EXPECT_EQ(mismatch.verdict, FinalTickVerifier::Verdict::kMismatch);
  EXPECT_EQ(mismatch.tick, 2);
  EXPECT_EQ(mismatch.local_checksum, server.checksums[2]);
  EXPECT_EQ(mismatch.server_checksum, wrong);
  // The mismatch is not agreement: it stops where the last match was.
  EXPECT_EQ(rig.verifier.agreed_through(), 1);
  EXPECT_EQ(rig.verifier.pending(), 1u);
}

TEST(FinalTickVerifier, AfterAResyncTakesOnlyAStandaloneTick) {
  const Authority server(8);
  VerifierRig rig;
  EXPECT_EQ(rig.verifier.apply(*rig.session, message({server.standalone(0), server.packed(1),
                                                      server.standalone(4)})),
            FinalTickVerifier::Applied::kOk);
  rig.simulate_through(1);
  EXPECT_EQ(rig.verifier.check_next(*rig.session).verdict, FinalTickVerifier::Verdict::kAgreed);

  // A snapshot at tick 6 loaded: it stands for ticks 1..5, of which only
  // tick 0 was verified; what was pending or held back is gone.
  EXPECT_EQ(rig.verifier.on_resync_loaded(6), 5u);
  EXPECT_EQ(rig.verifier.agreed_through(), 5);
  EXPECT_EQ(rig.verifier.last_received(), 5);
  EXPECT_EQ(rig.verifier.pending(), 0u);
  EXPECT_EQ(rig.verifier.held_back(), 0u);

  // The tick before 6 was never applied here, so a packed tick 6 cannot be
  // read: rejected, and nothing moves on.
  EXPECT_EQ(rig.verifier.apply(*rig.session, message({server.packed(6)})),
            FinalTickVerifier::Applied::kRejected);
  EXPECT_EQ(rig.verifier.last_received(), 5);
  EXPECT_EQ(rig.verifier.pending(), 0u);
}

}  // namespace
}  // namespace rwd::client
