// SPDX-License-Identifier: MIT
#include "rewind/server/websocket_port.h"

#include <algorithm>
#include <utility>

namespace rwd::server {
namespace {

// 100::/64, the discard-only prefix: the first eight bytes of the address;
// the last eight are the connection's serial.
constexpr uint8_t kPrefix[8] = {0x01, 0x00, 0, 0, 0, 0, 0, 0};

asio::ip::udp::endpoint endpoint_of(uint64_t serial, uint16_t tcp_port) {
  asio::ip::address_v6::bytes_type bytes{};
  std::copy(std::begin(kPrefix), std::end(kPrefix), bytes.begin());
  for (int i = 0; i < 8; ++i) bytes[15 - i] = static_cast<uint8_t>(serial >> (8 * i));
  return {asio::ip::address_v6(bytes), tcp_port};
}

uint64_t serial_of(const asio::ip::udp::endpoint& endpoint) {
  const auto bytes = endpoint.address().to_v6().to_bytes();
  uint64_t serial = 0;
  for (int i = 8; i < 16; ++i) serial = (serial << 8) | bytes[i];
  return serial;
}

}  // namespace

bool WebSocketPort::is_websocket_endpoint(const Endpoint& endpoint) {
  if (!endpoint.address().is_v6()) return false;
  const auto bytes = endpoint.address().to_v6().to_bytes();
  return std::equal(std::begin(kPrefix), std::end(kPrefix), bytes.begin());
}

Result<WebSocketPort::Endpoint> WebSocketPort::attach(std::shared_ptr<WebSocketPeer> peer,
                                                      uint16_t tcp_port) {
  std::lock_guard lock(mutex_);
  if (closed_) {
    ++stats_.refused;
    return Status::Error(ErrorCode::kNotFound, "the match has ended");
  }
  if (peers_.size() >= kMaxConnections) {
    ++stats_.refused;
    return Status::Error(ErrorCode::kCapacity, "the match has " + std::to_string(kMaxConnections) +
                                                   " WebSocket connections (the most)");
  }
  const uint64_t serial = next_serial_++;
  peers_.emplace(serial, std::move(peer));
  ++stats_.connections;
  return endpoint_of(serial, tcp_port);
}

void WebSocketPort::detach(const Endpoint& endpoint) {
  if (!is_websocket_endpoint(endpoint)) return;
  std::lock_guard lock(mutex_);
  peers_.erase(serial_of(endpoint));
}

void WebSocketPort::deliver(const Endpoint& from, std::span<const uint8_t> bytes) {
  std::lock_guard lock(mutex_);
  if (closed_ || waiting_.size() >= kMaxWaiting) {
    ++stats_.dropped_in;
    return;
  }
  waiting_.push_back(Waiting{from, waiting_bytes_.size(), bytes.size()});
  waiting_bytes_.insert(waiting_bytes_.end(), bytes.begin(), bytes.end());
}

size_t WebSocketPort::drain(const ReceiveHandler& handler) {
  {
    std::lock_guard lock(mutex_);
    draining_.clear();
    draining_bytes_.clear();
    std::swap(waiting_, draining_);
    std::swap(waiting_bytes_, draining_bytes_);
    stats_.datagrams_in += draining_.size();
    stats_.bytes_in += draining_bytes_.size();
  }
  for (const Waiting& datagram : draining_) {
    handler(std::span<const uint8_t>(draining_bytes_.data() + datagram.offset, datagram.size),
            datagram.from);
  }
  return draining_.size();
}

void WebSocketPort::send(std::span<const uint8_t> bytes, const Endpoint& to) {
  std::shared_ptr<WebSocketPeer> peer;
  {
    std::lock_guard lock(mutex_);
    const auto found = is_websocket_endpoint(to) ? peers_.find(serial_of(to)) : peers_.end();
    if (found == peers_.end()) {
      ++stats_.dropped_out;
      return;
    }
    peer = found->second;
    ++stats_.datagrams_out;
    stats_.bytes_out += bytes.size();
  }
  peer->send(std::vector<uint8_t>(bytes.begin(), bytes.end()));
}

void WebSocketPort::close() {
  std::unordered_map<uint64_t, std::shared_ptr<WebSocketPeer>> peers;
  {
    std::lock_guard lock(mutex_);
    if (closed_) return;
    closed_ = true;
    peers.swap(peers_);
    waiting_.clear();
    waiting_bytes_.clear();
  }
  for (auto& [serial, peer] : peers) peer->close();
}

WebSocketPort::Stats WebSocketPort::stats() const {
  std::lock_guard lock(mutex_);
  Stats out = stats_;
  out.open = peers_.size();
  return out;
}

}  // namespace rwd::server
