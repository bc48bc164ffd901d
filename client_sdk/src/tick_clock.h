// SPDX-License-Identifier: MIT
#pragma once
// ClientProtocol's sense of time in a match: the fractional tick clock that
// says which ticks are due, the server's tick as last heard, and the round
// trip measured by pings. One concern because they are one estimate: the
// clock starts (and is re-anchored after a resync) a round trip plus the
// target lead ahead of the server's tick, and net::TimeSync, fed the
// server's lead reports and the round trip, runs it a little fast or slow
// and jumps it when inputs arrive late.
//
// Plain arithmetic on a few numbers: no allocation, no messages built here
// beyond saying when a ping is due and what time it carries.
#include <cstdint>

#include "rewind/core/tick.h"
#include "rewind/net/clock.h"
#include "rewind/net/time_sync.h"

namespace rwd::client {

class TickClock {
 public:
  using TimePoint = net::TimePoint;

  explicit TickClock(double target_lead_ticks)
      : target_lead_ticks_(target_lead_ticks), time_sync_(net::TimeSyncConfig{target_lead_ticks}) {}

  /// Time runs from `now` (a join starts).
  void start(TimePoint now) { last_update_ = now; }
  /// Seconds since the last call (0 when time went backwards, which then
  /// counts as no time passing).
  double elapse(TimePoint now);

  void set_tick_rate(uint32_t hz) { tick_rate_hz_ = hz; }
  double period_s() const { return 1.0 / tick_rate_hz_; }

  /// The round trip of the join exchange, the first sample when no pong
  /// has come yet.
  void seed_round_trip(double rtt_ms);
  double rtt_ms() const { return rtt_ms_; }

  /// The match started at the server's `server_tick`: the clock starts a
  /// round trip plus the target lead ahead of it, and runs from `now`.
  void start_match(Tick server_tick, TimePoint now);
  /// Advances the clock by `dt_s`, scaled by the time sync, plus any jump.
  void run(double dt_s);
  /// The tick the clock has reached, held at `barrier` + 1 (the clock waits
  /// there instead of running on and bursting later): ticks before it are due.
  Tick due_through(Tick barrier);
  /// After a resync snapshot at `tick`: re-anchored on the server's tick,
  /// never before `tick`, with pending jumps forgotten.
  void reanchor(Tick tick);

  /// Whether a ping is due (every 100 ms in the lobby, 250 ms in a match);
  /// true restarts the interval.
  bool ping_due(TimePoint now, bool lobby);
  /// The next ping_due() is true, whatever the interval.
  void ping_now(TimePoint now);
  /// The time a ping carries, which its pong echoes.
  static uint64_t client_time_us(TimePoint t);
  /// A pong to a ping sent at `client_time_us`: a round-trip sample, and
  /// the server's tick when it answered.
  void on_pong(uint64_t client_time_us, Tick server_tick, TimePoint now);

  /// The server's tick as a final-ticks message reports it.
  void on_server_tick(Tick server_tick);
  /// How early our newest input reached the server (net::TimeSync).
  void on_lead_report(int32_t lead_ticks) { time_sync_.on_lead_report(lead_ticks); }

  /// `current` minus the server's tick estimated for now.
  int32_t ticks_ahead(Tick current) const;
  double smoothed_lead() const { return time_sync_.smoothed_lead(); }

 private:
  double rtt_ticks() const { return rtt_ms_ / 1000.0 * tick_rate_hz_; }

  double target_lead_ticks_;
  net::TimeSync time_sync_;
  uint32_t tick_rate_hz_ = 60;
  double rtt_ms_ = 0.0;  // smoothed; reported as ClientStats::rtt_ms
  Tick server_tick_ = 0;
  // Fractional ticks, advanced by the time given scaled by the time sync,
  // so steps happen at the right moments.
  double tick_clock_ = 0.0;
  TimePoint last_update_;
  TimePoint last_ping_;
};

}  // namespace rwd::client
