// SPDX-License-Identifier: MIT
#include "rewind/server/agones_health_pinger.h"

#include "rewind/server/server_log.h"

namespace rwd::server {

AgonesHealthPinger::AgonesHealthPinger(const AgonesSdk& sdk, std::chrono::milliseconds period,
                                       HealthFn health)
    : sdk_(sdk), period_(period), health_(std::move(health)), thread_([this] { run(); }) {}

AgonesHealthPinger::~AgonesHealthPinger() {
  stop();
}

void AgonesHealthPinger::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void AgonesHealthPinger::run() {
  auto next = std::chrono::steady_clock::now();
  std::unique_lock<std::mutex> lock(mutex_);
  bool withholding = false;
  while (!stopping_) {
    lock.unlock();
    const std::string problem = health_ ? health_() : std::string();
    if (!problem.empty() && !withholding) {
      write_log(
          LogLevel::kWarning,
          "agones: health pings withheld, so Agones marks this GameServer Unhealthy: " + problem);
    } else if (problem.empty() && withholding) {
      write_log(LogLevel::kInfo, "agones: healthy again after " + std::to_string(withheld_.load()) +
                                     " withheld health pings; pinging again");
    }
    withholding = !problem.empty();
    if (withholding) {
      withheld_.fetch_add(1);
    } else {
      const Status status = sdk_.health();
      sent_.fetch_add(1);
      if (!status.ok()) {
        const uint64_t failures = failed_.fetch_add(1) + 1;
        write_log(LogLevel::kWarning, "agones: health ping failed (" + std::to_string(failures) +
                                          " of " + std::to_string(sent_.load()) +
                                          " so far): " + status.message());
      }
    }
    // On a fixed grid, so a slow ping does not stretch the period; after a
    // ping longer than the period the grid restarts from now.
    next += period_;
    const auto now = std::chrono::steady_clock::now();
    if (next < now) next = now;
    lock.lock();
    wake_.wait_until(lock, next, [this] { return stopping_; });
  }
}

}  // namespace rwd::server
