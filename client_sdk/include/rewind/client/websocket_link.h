// SPDX-License-Identifier: MIT
#pragma once
// A client's datagrams over a WebSocket connection, the way browsers reach
// a server (rewind-server --websocket): each datagram is one binary
// message. Native programs use it to play or load-test the browser path
// (rewind-bots --websocket); pair it with ClientSession::create_detached:
//
//   auto link = WebSocketLink::open("ws://127.0.0.1:7800/matches/duel-7");
//   auto session = ClientSession::create_detached(
//       config, [&](std::span<const uint8_t> d) { (*link)->send(d); });
//   ... every frame:
//   (*link)->poll([&](std::span<const uint8_t> d) { session->receive(d, now); });
//   session->update(now);
//
// Nothing blocks: open() starts connecting and poll() advances the
// connection. Datagrams sent before it is open wait (up to kMaxWaiting
// bytes; older ones are dropped first, like datagrams lost in a queue).
// ws:// only: no TLS. Not thread-safe: one thread at a time.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "rewind/core/status.h"

namespace rwd::client {

class WebSocketLink {
 public:
  using MessageFn = std::function<void(std::span<const uint8_t> datagram)>;
  static constexpr size_t kMaxWaiting = 256 * 1024;

  enum class State : uint8_t { kConnecting, kOpen, kClosed };

  struct Stats {
    uint64_t messages_in = 0;
    uint64_t bytes_in = 0;
    uint64_t messages_out = 0;
    uint64_t bytes_out = 0;
    uint64_t dropped_out = 0;  ///< over kMaxWaiting, or after the connection closed
  };

  /// Starts connecting to `url`: ws://HOST:PORT/PATH (HOST a name or an IP
  /// literal, [v6] in brackets). kInvalidArgument for anything else, wss://
  /// included.
  static Result<std::unique_ptr<WebSocketLink>> open(std::string_view url);
  ~WebSocketLink();
  WebSocketLink(const WebSocketLink&) = delete;
  WebSocketLink& operator=(const WebSocketLink&) = delete;

  /// Queues one datagram for the server.
  void send(std::span<const uint8_t> datagram);
  /// Runs whatever is ready (resolving, connecting, reading, writing) and
  /// hands each message received to `on_message`; returns how many.
  size_t poll(const MessageFn& on_message);
  /// Closes the connection (a WebSocket close, then the socket).
  void close();

  State state() const;
  /// Why the connection closed or never opened; empty while it is fine.
  const std::string& error() const;
  Stats stats() const;

  struct Impl;

 private:
  explicit WebSocketLink(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace rwd::client
