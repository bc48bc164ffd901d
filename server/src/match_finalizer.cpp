// SPDX-License-Identifier: MIT
#include "rewind/server/match_finalizer.h"

#include <algorithm>
#include <string>

namespace rwd::server {
namespace {

constexpr size_t kFinalTicksBudgetBytes = 1000;  // leaves room for the envelope header
constexpr size_t kMaxFinalHistory = 1024;        // ticks kept for clients that fall behind

}  // namespace

MatchFinalizer::MatchFinalizer(const MatchConfig& config, net::RollbackSession& session,
                               const MatchSeats& seats, MatchRecorder& recorder, MatchStats& stats)
    : config_(config),
      session_(session),
      seats_(seats),
      recorder_(recorder),
      stats_(stats),
      history_(kFinalHistory),
      final_inputs_(config.players) {}

void MatchFinalizer::finalize_ready_ticks() {
  const Tick current = session_.current_tick();
  const std::span<const Seat> players = seats_.player_seats();
  while (next_final_ < current) {
    if (config_.max_ticks > 0 && next_final_ >= config_.max_ticks) break;
    const Tick t = next_final_;
    // A slot nobody holds (not taken yet, timed out, left) sends nothing:
    // waiting the window for it would only delay every tick.
    bool all_known = true;
    for (uint32_t p = 0; p < players.size(); ++p) {
      all_known = all_known && (!players[p].present() || session_.queue(p).is_confirmed(t));
    }
    if (!all_known && current - t < config_.window_ticks) break;

    uint64_t substituted = 0;
    for (uint32_t p = 0; p < players.size(); ++p) {
      if (!session_.queue(p).is_confirmed(t)) {
        substituted |= uint64_t{1} << p;
        (void)session_.add_final_input(p, t, session_.input_for(p, t));
        ++stats_.substituted_inputs;
      }
      final_inputs_[p] = session_.input_for(p, t);
    }
    const uint64_t checksum = session_.checksum_after(t).value_or(0);
    history_[static_cast<size_t>(t) % kFinalHistory] = {t, substituted, checksum};
    stats_.final_checksum = checksum;

    recorder_.record(session_, t, final_inputs_, substituted, checksum, stats_);
    (void)session_.finalize_through(t);
    finals_.append(t, final_inputs_, substituted, checksum, current);
    ++next_final_;
  }
  if (recorder_.names_stale()) {
    std::vector<std::string> names;
    for (const Seat& seat : players) names.push_back(seat.joined ? seat.name : std::string());
    recorder_.publish_names(std::move(names));
  }
  // Drop history every connected client has; keep a bounded tail for the rest.
  finals_.trim(seats_.acknowledged_by_all(next_final_ - 1), kMaxFinalHistory);
}

std::optional<uint64_t> MatchFinalizer::checksum(Tick tick) const {
  if (tick < 0) return std::nullopt;
  const FinalRecord& record = history_[static_cast<size_t>(tick) % kFinalHistory];
  if (record.tick != tick) return std::nullopt;
  return record.checksum;
}

bool MatchFinalizer::substituted(Tick tick, uint32_t player) const {
  if (tick < 0 || player >= 64) return false;
  const FinalRecord& record = history_[static_cast<size_t>(tick) % kFinalHistory];
  return record.tick == tick && ((record.substituted >> player) & 1u) != 0;
}

void MatchFinalizer::compose(Seat& seat, uint32_t id, Tick server_tick, const InputRelay& relay,
                             bool resync_pending, v1::FinalTicks& out) const {
  const bool player = seats_.is_player(id);  // spectators send no inputs
  out.set_input_ack_tick(player ? session_.queue(id).contiguous_through() : kNoTick);
  out.set_input_lead_ticks(seat.last_lead);
  out.set_server_tick(server_tick);
  // The other players' new inputs first (they are what prediction waits
  // for), up to part of the budget: what does not fit arrives in final
  // ticks soon anyway.
  size_t budget = kFinalTicksBudgetBytes - 3;  // the relayed field's tag and length
  budget = relay.append_for(id, budget, kFinalTicksBudgetBytes / 3, *out.mutable_relayed());
  // While a snapshot is on its way the client ignores final ticks, but
  // still needs the server's clock and its input acknowledgements.
  if (resync_pending) return;
  const double rtt_ticks =
      seat.connection->has_rtt()
          ? static_cast<double>(seat.connection->smoothed_rtt_us()) * config_.tick_rate_hz / 1e6
          : 0.0;
  FinalTickLog::Cursor cursor{seat.final_seen, seat.final_sent, seat.resend_cursor,
                              seat.standalone_from};
  finals_.add_to(out, budget, cursor, session_.current_tick(), rtt_ticks);
  seat.final_sent = cursor.sent;
  seat.resend_cursor = cursor.resend;
}

}  // namespace rwd::server
