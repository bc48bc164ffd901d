// SPDX-License-Identifier: MIT
#pragma once
// Agones health pings on their own thread: POST /health at once and then
// every `period` until stop(), so a slow or absent sidecar never stalls the
// tick loop. A failed ping is logged as a warning and counted; it never
// ends the match (Agones itself decides when missed pings make the
// GameServer Unhealthy). While the process says it is not healthy (its
// ticks slip persistently: LoadMonitor::healthy) pings are withheld, so
// Agones marks the GameServer Unhealthy and replaces it rather than
// keeping players on a server that cannot hold its tick rate.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "rewind/server/agones_sdk.h"

namespace rwd::server {

class AgonesHealthPinger {
 public:
  /// Why the process is not healthy now, or empty when it is; called from
  /// the pinger's thread before each ping.
  using HealthFn = std::function<std::string()>;

  /// Starts pinging through `sdk`, which must outlive this object.
  /// `period` is the time between the starts of two pings, > 0. With
  /// `health`, a ping is withheld while it names a problem.
  AgonesHealthPinger(const AgonesSdk& sdk, std::chrono::milliseconds period, HealthFn health = {});
  /// Stops (see stop()).
  ~AgonesHealthPinger();
  AgonesHealthPinger(const AgonesHealthPinger&) = delete;
  AgonesHealthPinger& operator=(const AgonesHealthPinger&) = delete;

  /// Ends the pinging: waits for a ping in flight (at most the SDK's call
  /// deadline), then joins the thread. Idempotent.
  void stop();
  /// Pings sent so far, successful or not.
  uint64_t sent() const { return sent_.load(); }
  /// Pings that failed (no answer, or an answer other than 2xx).
  uint64_t failed() const { return failed_.load(); }
  /// Pings withheld because the process was not healthy.
  uint64_t withheld() const { return withheld_.load(); }

 private:
  void run();

  const AgonesSdk& sdk_;
  std::chrono::milliseconds period_;
  HealthFn health_;
  std::atomic<uint64_t> sent_{0};
  std::atomic<uint64_t> withheld_{0};
  std::atomic<uint64_t> failed_{0};
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;  ///< guarded by mutex_
  std::thread thread_;     ///< last: started once the rest is set up
};

}  // namespace rwd::server
