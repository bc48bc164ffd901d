// SPDX-License-Identifier: MIT
#pragma once
// The server's authoritative inputs and our check against its checksums:
// other players' inputs as relayed (predictions to correct), and final
// ticks applied strictly in order, each one's inputs possibly packed
// against the tick before (always the one applied last), with ticks that
// arrive ahead of a gap held back (bounded by the rollback depth). Each
// applied tick waits with the server's checksum until we have simulated it;
// then our own checksum after it either agrees (agreed_through() moves on)
// or does not (a desync, for the protocol to report).
//
// It holds no phase and sends nothing: what it finds (a tick beyond our
// input window, history we can no longer re-simulate, a mismatch) is
// returned for the protocol to act on, which keeps it testable on a bare
// RollbackSession. Its buffers keep their capacity between messages.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "rewind/core/player_input.h"
#include "rewind/core/tick.h"
#include "rewind/net/rollback_session.h"
#include "rewind/proto/message_inputs.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::client {

class FinalTickVerifier {
 public:
  /// What apply() made of a FinalTicks message.
  enum class Applied : uint8_t {
    kOk,        ///< every tick applied, held back for a gap, or a duplicate
    kRejected,  ///< a tick's inputs did not decode: count it; the rest wait for a resend
    kTooFar,    ///< a tick beyond our input window: only a resync can help
  };
  /// What check_next() found.
  enum class Verdict : uint8_t {
    kNone,      ///< no applied tick we have simulated yet
    kAgreed,    ///< our checksum matches the server's
    kMismatch,  ///< it does not: a desync
    kLost,      ///< we can no longer re-simulate the tick: only a resync can help
  };
  struct Check {
    Verdict verdict = Verdict::kNone;
    Tick tick = kNoTick;
    uint64_t local_checksum = 0;
    uint64_t server_checksum = 0;
  };

  /// `snapshot_ticks`: the rollback depth, which bounds the ticks held
  /// back ahead of a gap.
  explicit FinalTickVerifier(int32_t snapshot_ticks) : snapshot_ticks_(snapshot_ticks) {}

  /// Our seat: inputs relayed for `player` are our own and ignored, and
  /// every final tick carries `player_count` inputs.
  void seat(uint32_t player, uint32_t player_count);

  /// Another player's inputs from `first_tick` on, as the server relayed them.
  void on_relayed(net::RollbackSession& session, uint32_t player, Tick first_tick,
                  std::span<const rwd::PlayerInput> inputs);
  /// A RelayedInputs message (checked by decode_envelope).
  void on_relayed(net::RollbackSession& session, const v1::RelayedInputs& run);
  /// The relayed runs a FinalTicks message carries (checked by decode_envelope).
  void on_relayed_runs(net::RollbackSession& session, const v1::FinalTicks& finals);

  /// Applies the message's final ticks in order from last_received() + 1,
  /// holding back those ahead of a gap and applying them once it closes.
  Applied apply(net::RollbackSession& session, const v1::FinalTicks& finals);
  /// Checks the oldest applied tick once `session` has simulated it.
  /// kAgreed and kMismatch consume it; kLost leaves it.
  Check check_next(net::RollbackSession& session);

  /// The newest final tick applied (in order).
  Tick last_received() const { return last_final_received_; }
  /// The last final tick our state is known to agree on: verified, or
  /// passed over by a resync snapshot whose checksum matched.
  Tick agreed_through() const { return agreed_through_; }
  size_t pending() const { return pending_finals_.size(); }
  size_t held_back() const { return early_finals_.size(); }

  /// A resync snapshot at `tick` loaded: the server resends final ticks
  /// from there (the first standalone), and the snapshot stands for the
  /// ticks before it. Returns how many of those we had not verified.
  uint64_t on_resync_loaded(Tick tick);

 private:
  /// Applies the next final tick; false stops the message (`failure` says why).
  bool apply_one(net::RollbackSession& session, const v1::FinalTick& final_tick, Applied& failure);

  int32_t snapshot_ticks_;
  uint32_t player_ = 0;
  uint32_t player_count_ = 0;
  Tick last_final_received_ = kNoTick;
  Tick agreed_through_ = kNoTick;
  std::deque<std::pair<Tick, uint64_t>> pending_finals_;  // (tick, server checksum)
  std::map<Tick, v1::FinalTick> early_finals_;            // arrived ahead of a gap, bounded
  /// The final inputs of tick last_final_received_ (empty after a resync:
  /// the server then sends the next tick standalone).
  std::vector<rwd::PlayerInput> last_final_inputs_;
  std::vector<rwd::PlayerInput> final_inputs_buffer_;
  std::vector<rwd::PlayerInput> relayed_buffer_;
  std::vector<proto::RelayedRun> relayed_runs_;
};

}  // namespace rwd::client
