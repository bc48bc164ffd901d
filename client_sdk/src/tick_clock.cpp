// SPDX-License-Identifier: MIT
#include "tick_clock.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rwd::client {
namespace {

constexpr auto kLobbyPing = std::chrono::milliseconds(100);
constexpr auto kMatchPing = std::chrono::milliseconds(250);

}  // namespace

double TickClock::elapse(TimePoint now) {
  const double dt = std::max(0.0, std::chrono::duration<double>(now - last_update_).count());
  last_update_ = std::max(last_update_, now);
  return dt;
}

void TickClock::seed_round_trip(double rtt_ms) {
  if (rtt_ms_ == 0.0) rtt_ms_ = rtt_ms;
}

void TickClock::start_match(Tick server_tick, TimePoint now) {
  server_tick_ = server_tick;
  // The announced server tick is a one-way delay old when it arrives, and
  // our inputs take another one-way delay to reach the server: start a
  // round trip plus the target lead ahead of the announced tick.
  const double rtt = rtt_ticks();
  tick_clock_ = server_tick + rtt + target_lead_ticks_;
  time_sync_.set_round_trip_ticks(rtt);
  last_update_ = now;
}

void TickClock::run(double dt_s) {
  // The tick clock runs a little fast or slow to keep our inputs arriving
  // just ahead of the server's need.
  tick_clock_ += dt_s / (period_s() * time_sync_.period_scale());
  tick_clock_ += time_sync_.take_jump();
}

Tick TickClock::due_through(Tick barrier) {
  tick_clock_ = std::min(tick_clock_, static_cast<double>(barrier) + 1.0);
  return static_cast<Tick>(std::floor(tick_clock_));
}

void TickClock::reanchor(Tick tick) {
  // Re-anchor the clock on the server's instead of bursting through the
  // ticks the clock ran ahead while we waited.
  tick_clock_ =
      std::max(static_cast<double>(tick), server_tick_ + rtt_ticks() + target_lead_ticks_);
  time_sync_.clear_jump();
}

bool TickClock::ping_due(TimePoint now, bool lobby) {
  if (now - last_ping_ < (lobby ? kLobbyPing : kMatchPing)) return false;
  last_ping_ = now;
  return true;
}

void TickClock::ping_now(TimePoint now) {
  last_ping_ = now - kLobbyPing;
}

uint64_t TickClock::client_time_us(TimePoint t) {
  return static_cast<uint64_t>(
      std::chrono::duration_cast<std::chrono::microseconds>(t.time_since_epoch()).count());
}

void TickClock::on_pong(uint64_t client_time_us, Tick server_tick, TimePoint now) {
  const double rtt_ms =
      (static_cast<double>(TickClock::client_time_us(now)) - static_cast<double>(client_time_us)) /
      1000.0;
  if (rtt_ms >= 0 && rtt_ms < 10000) {
    rtt_ms_ = rtt_ms_ == 0.0 ? rtt_ms : rtt_ms_ + 0.125 * (rtt_ms - rtt_ms_);
    time_sync_.set_round_trip_ticks(rtt_ticks());
  }
  server_tick_ = std::max(server_tick_, server_tick);
}

void TickClock::on_server_tick(Tick server_tick) {
  server_tick_ = std::max(server_tick_, server_tick);
}

int32_t TickClock::ticks_ahead(Tick current) const {
  const double one_way_ticks = rtt_ms_ / 2000.0 * tick_rate_hz_;
  return static_cast<int32_t>(std::lround(current - (server_tick_ + one_way_ticks)));
}

}  // namespace rwd::client
