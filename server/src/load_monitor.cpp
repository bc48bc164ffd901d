// SPDX-License-Identifier: MIT
#include "rewind/server/load_monitor.h"

#include <algorithm>
#include <cstdio>

namespace rwd::server {
namespace {

std::string percent(double share) {
  char text[16];
  std::snprintf(text, sizeof text, "%.0f%%", share * 100.0);
  return text;
}

}  // namespace

LoadMonitor::LoadMonitor(double tick_budget, net::TimePoint now)
    : tick_budget_(tick_budget), first_second_(second_of(now)) {}

int64_t LoadMonitor::second_of(net::TimePoint t) {
  return std::chrono::floor<std::chrono::seconds>(t.time_since_epoch()).count();
}

const LoadMonitor::Second* LoadMonitor::find(int64_t second) const {
  const Second& s = seconds_[static_cast<size_t>(second) % kSeconds];
  return s.second == second ? &s : nullptr;
}

bool LoadMonitor::slipped(const Second& s) {
  const uint64_t due = s.ticks + s.missed;
  return static_cast<double>(s.late + s.missed) > kSlipShare * static_cast<double>(due);
}

void LoadMonitor::set_threads(uint32_t threads) {
  std::lock_guard lock(mutex_);
  threads_ = std::max(1u, threads);
}

void LoadMonitor::match_started(net::TimePoint now) {
  std::lock_guard lock(mutex_);
  if (live_++ == 0) live_since_second_ = second_of(now);
  last_tick_ = std::max(last_tick_, now);
}

void LoadMonitor::match_ended() {
  std::lock_guard lock(mutex_);
  if (live_ > 0) --live_;
}

void LoadMonitor::record_tick(net::TimePoint start, std::chrono::nanoseconds work, bool late,
                              uint64_t missed) {
  const int64_t second = second_of(start);
  std::lock_guard lock(mutex_);
  Second& s = seconds_[static_cast<size_t>(second) % kSeconds];
  if (s.second != second) {
    // A tick of a second already overwritten (a match thread that read its
    // clock long ago) is left out rather than mixed into a newer second.
    if (s.second > second) return;
    s = Second{};
    s.second = second;
  }
  s.busy_ns += static_cast<uint64_t>(std::max<int64_t>(0, work.count()));
  ++s.ticks;
  s.late += late ? 1 : 0;
  s.missed += missed;
  last_tick_ = std::max(last_tick_, start);
}

LoadMonitor::Load LoadMonitor::load(net::TimePoint now) const {
  const int64_t now_s = second_of(now);
  std::lock_guard lock(mutex_);
  Load out;
  out.threads = threads_;
  out.live = live_;
  out.stalled = live_ > 0 && now - last_tick_ > kStalledAfter;
  // The whole seconds before the current one, none from before the start.
  const int64_t first = std::max(now_s - kWindowS, first_second_);
  uint64_t busy_ns = 0;
  for (int64_t second = first; second < now_s; ++second) {
    if (const Second* s = find(second)) {
      busy_ns += s->busy_ns;
      out.ticks += s->ticks;
      out.late += s->late;
      out.missed += s->missed;
    }
  }
  out.window_s = static_cast<double>(std::max<int64_t>(0, now_s - first));
  if (out.window_s > 0) {
    out.busy = static_cast<double>(busy_ns) / 1e9 / (out.window_s * threads_);
  }
  const uint64_t due = out.ticks + out.missed;
  out.slipping = static_cast<double>(out.late + out.missed) > kSlipShare * static_cast<double>(due);
  // Seconds in a row that slipped, back from the last whole one. While
  // matches are live, a second in which none of them ticked slipped too.
  const int64_t most = static_cast<int64_t>(kSeconds) - 1;  // what the ring still holds
  for (int64_t second = now_s - 1; second >= first_second_ && out.slipping_s < most; --second) {
    const Second* s = find(second);
    const bool quiet = s == nullptr || s->ticks + s->missed == 0;
    if (quiet ? !(live_ > 0 && second >= live_since_second_) : !slipped(*s)) break;
    ++out.slipping_s;
  }
  return out;
}

std::string LoadMonitor::overload_reason(net::TimePoint now) const {
  const Load l = load(now);
  if (l.stalled) {
    return "overloaded: " + std::to_string(l.live) + " matches are live but none has ticked for " +
           std::to_string(kStalledAfter.count()) + " s";
  }
  if (l.slipping) {
    return "overloaded: " + std::to_string(l.late + l.missed) + " of the " +
           std::to_string(l.ticks + l.missed) + " ticks due in the last " +
           std::to_string(static_cast<int64_t>(l.window_s)) +
           " s started a period late or were dropped";
  }
  if (l.busy > tick_budget_) {
    return "overloaded: the " + std::to_string(l.threads) + " match threads spent " +
           percent(l.busy) + " of the last " + std::to_string(static_cast<int64_t>(l.window_s)) +
           " s ticking (budget " + percent(tick_budget_) + ", --tick-budget)";
  }
  return {};
}

bool LoadMonitor::healthy(net::TimePoint now) const {
  return unhealthy_reason(now).empty();
}

std::string LoadMonitor::unhealthy_reason(net::TimePoint now) const {
  const Load l = load(now);
  if (l.stalled) {
    return std::to_string(l.live) + " matches are live but none has ticked for " +
           std::to_string(kStalledAfter.count()) + " s";
  }
  if (l.slipping_s >= kUnhealthyAfterS) {
    return "ticks have slipped (over " + percent(kSlipShare) +
           " started a period late or were dropped) for " + std::to_string(l.slipping_s) +
           " s in a row";
  }
  return {};
}

}  // namespace rwd::server
