// SPDX-License-Identifier: MIT
#include "rewind/net/fault_injector.h"

#include "rewind/core/splitmix64.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include <asio/error.hpp>
#include <asio/steady_timer.hpp>

namespace rwd::net {
namespace {

using SteadyTime = std::chrono::steady_clock::time_point;

constexpr uint32_t kMaxDelayMs = 10'000;

Status check_probability(const char* field, double p) {
  // Written so that NaN fails too.
  if (!(p >= 0.0 && p <= 1.0)) {
    return Status::Error(
        ErrorCode::kInvalidArgument,
        std::string("fault config: ") + field + " = " + std::to_string(p) + " not in [0, 1]");
  }
  return Status::Ok();
}

Status check_delay(const char* field, uint32_t ms, uint32_t min_ms) {
  if (ms < min_ms || ms > kMaxDelayMs) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         std::string("fault config: ") + field + " = " + std::to_string(ms) +
                             " ms not in [" + std::to_string(min_ms) + ", 10000]");
  }
  return Status::Ok();
}

constexpr uint64_t rotl(uint64_t x, int k) {
  return (x << k) | (x >> (64 - k));
}

}  // namespace

Status validate_fault_config(const FaultConfig& c) {
  if (Status s = check_probability("loss", c.loss); !s.ok()) return s;
  if (Status s = check_probability("duplicate", c.duplicate); !s.ok()) return s;
  if (Status s = check_probability("reorder", c.reorder); !s.ok()) return s;
  if (Status s = check_delay("latency_ms", c.latency_ms, 0); !s.ok()) return s;
  if (Status s = check_delay("jitter_ms", c.jitter_ms, 0); !s.ok()) return s;
  return check_delay("reorder_hold_ms", c.reorder_hold_ms, 1);
}

// ---------------------------------------------------------------------------
// FaultInjector

Result<FaultInjector> FaultInjector::create(const FaultConfig& config) {
  if (Status s = validate_fault_config(config); !s.ok()) return s;
  return FaultInjector(config);
}

FaultInjector::FaultInjector(const FaultConfig& config) : config_(config) {
  // splitmix64 expands the seed as the xoshiro authors recommend; it never
  // yields the all-zero state for four consecutive outputs.
  SplitMix64 seeder{config.seed};
  for (uint64_t& word : state_) word = seeder.next();
}

uint64_t FaultInjector::next() {
  // xoshiro256** 1.0
  const uint64_t result = rotl(state_[1] * 5, 7) * 9;
  const uint64_t t = state_[1] << 17;
  state_[2] ^= state_[0];
  state_[3] ^= state_[1];
  state_[1] ^= state_[2];
  state_[0] ^= state_[3];
  state_[2] ^= t;
  state_[3] = rotl(state_[3], 45);
  return result;
}

double FaultInjector::next_unit() {
  return static_cast<double>(next() >> 11) * 0x1.0p-53;
}

uint32_t FaultInjector::next_delay_ms() {
  const uint64_t draw = next();
  if (config_.jitter_ms == 0) return config_.latency_ms;
  const uint64_t span = 2ull * config_.jitter_ms + 1;
  // Multiply-shift maps the high 32 bits onto [0, span) without a division.
  const auto offset =
      static_cast<int64_t>(((draw >> 32) * span) >> 32) - static_cast<int64_t>(config_.jitter_ms);
  return static_cast<uint32_t>(std::max<int64_t>(0, int64_t{config_.latency_ms} + offset));
}

PacketFate FaultInjector::decide() {
  // Draw everything up front: a fixed number of draws per packet keeps the
  // stream aligned, so changing `loss` does not reshuffle every later delay.
  const double u_loss = next_unit();
  const double u_duplicate = next_unit();
  const double u_reorder = next_unit();
  const uint32_t delay = next_delay_ms();
  const uint32_t duplicate_delay = next_delay_ms();

  PacketFate fate;
  if (u_loss < config_.loss) {
    fate.dropped = true;
    return fate;
  }
  fate.duplicated = u_duplicate < config_.duplicate;
  fate.reordered = u_reorder < config_.reorder;
  fate.delay_ms = delay + (fate.reordered ? config_.reorder_hold_ms : 0);
  fate.duplicate_delay_ms = fate.duplicated ? duplicate_delay : 0;
  return fate;
}

// ---------------------------------------------------------------------------
// FaultyLink

struct FaultyLink::State {
  State(asio::io_context& io, FaultInjector inj, SendFunction fn, size_t max)
      : timer(io), injector(std::move(inj)), send(std::move(fn)), max_queued(max) {}

  struct Queued {
    SteadyTime due;
    uint64_t order = 0;  // FIFO among equal due times
    Endpoint to;
    std::vector<uint8_t> bytes;
  };
  struct Later {
    bool operator()(const Queued& a, const Queued& b) const {
      return a.due != b.due ? a.due > b.due : a.order > b.order;
    }
  };

  asio::steady_timer timer;
  FaultInjector injector;
  SendFunction send;
  size_t max_queued;
  std::priority_queue<Queued, std::vector<Queued>, Later> queue;
  uint64_t next_order = 0;
  bool armed = false;
  SteadyTime armed_for{};
  bool closed = false;
  Stats stats;

  void deliver(std::span<const uint8_t> bytes, const Endpoint& to) {
    ++stats.delivered;
    // Moved out for the call: the send function may destroy the link, which
    // clears `send` while it runs.
    SendFunction fn = std::exchange(send, nullptr);
    fn(bytes, to);
    if (!closed && !send) send = std::move(fn);
  }

  void enqueue(std::span<const uint8_t> bytes, const Endpoint& to, uint32_t delay_ms,
               SteadyTime now) {
    if (delay_ms == 0) {
      deliver(bytes, to);
      return;
    }
    if (queue.size() >= max_queued) {
      ++stats.dropped_overflow;
      return;
    }
    queue.push(Queued{now + std::chrono::milliseconds(delay_ms), next_order++, to,
                      std::vector<uint8_t>(bytes.begin(), bytes.end())});
  }

  static void arm(const std::shared_ptr<State>& self) {
    if (self->closed || self->queue.empty()) return;
    const SteadyTime due = self->queue.top().due;
    if (self->armed && self->armed_for <= due) return;
    self->armed = true;
    self->armed_for = due;
    // expires_at cancels the previous wait; its handler sees operation_aborted.
    self->timer.expires_at(due);
    self->timer.async_wait([self](const std::error_code& ec) {
      if (ec == asio::error::operation_aborted || self->closed) return;
      self->armed = false;
      flush(self);
      arm(self);
    });
  }

  static void flush(const std::shared_ptr<State>& self) {
    const SteadyTime now = std::chrono::steady_clock::now();
    while (!self->closed && !self->queue.empty() && self->queue.top().due <= now) {
      // priority_queue::top is const; the element is popped right after.
      Queued packet = std::move(const_cast<Queued&>(self->queue.top()));
      self->queue.pop();
      self->deliver(packet.bytes, packet.to);
    }
  }
};

Result<FaultyLink> FaultyLink::create(asio::io_context& io, const FaultConfig& config,
                                      SendFunction send, size_t max_queued) {
  Result<FaultInjector> injector = FaultInjector::create(config);
  if (!injector.ok()) return injector.status();
  if (!send) return Status::Error(ErrorCode::kInvalidArgument, "faulty link: empty send function");
  if (max_queued == 0)
    return Status::Error(ErrorCode::kInvalidArgument, "faulty link: max_queued 0");
  return FaultyLink(
      std::make_shared<State>(io, std::move(injector.value()), std::move(send), max_queued));
}

FaultyLink::FaultyLink(std::shared_ptr<State> state) : state_(std::move(state)) {}

FaultyLink& FaultyLink::operator=(FaultyLink&& other) noexcept {
  if (this != &other) {
    shutdown();
    state_ = std::move(other.state_);
  }
  return *this;
}

FaultyLink::~FaultyLink() {
  shutdown();
}

void FaultyLink::shutdown() {
  if (!state_) return;
  state_->closed = true;
  state_->send = nullptr;
  state_->queue = {};
  state_->timer.cancel();
}

void FaultyLink::send(std::span<const uint8_t> bytes, const Endpoint& to) {
  if (!state_) return;
  // The send function may destroy this link; keep the state alive meanwhile.
  const std::shared_ptr<State> keep = state_;
  State& s = *keep;
  if (s.closed) return;
  ++s.stats.offered;
  const PacketFate fate = s.injector.decide();
  if (bytes.size() > kMaxPayloadBytes) {
    ++s.stats.dropped_overflow;
    return;
  }
  if (fate.dropped) {
    ++s.stats.dropped_loss;
    return;
  }
  if (fate.reordered) ++s.stats.reordered;
  if (fate.duplicated) ++s.stats.duplicated;
  const auto now = std::chrono::steady_clock::now();
  s.enqueue(bytes, to, fate.delay_ms, now);
  if (fate.duplicated && !s.closed) s.enqueue(bytes, to, fate.duplicate_delay_ms, now);
  State::arm(keep);
}

size_t FaultyLink::queued() const {
  return state_ ? state_->queue.size() : 0;
}

const FaultyLink::Stats& FaultyLink::stats() const {
  static const Stats kEmpty;
  return state_ ? state_->stats : kEmpty;
}

}  // namespace rwd::net
