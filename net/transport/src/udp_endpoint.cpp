// SPDX-License-Identifier: MIT
#include "rewind/net/udp_endpoint.h"

#include <array>
#include <string>
#include <utility>

#include <asio/buffer.hpp>
#include <asio/error.hpp>

namespace rwd::net {

struct UdpEndpoint::State {
  explicit State(asio::io_context& io) : socket(io) {}

  asio::ip::udp::socket socket;
  Endpoint local;
  Endpoint sender;
  std::array<uint8_t, kReceiveBufferBytes> buffer{};
  ReceiveHandler on_receive;
  ErrorHandler on_error;
  bool receiving = false;
  Stats stats;

  void report(std::string_view operation, const std::error_code& error) {
    stats.last_error = error;
    if (!on_error) return;
    // Moved out for the call, so the handler may close() or replace itself.
    ErrorHandler handler = std::exchange(on_error, nullptr);
    handler(operation, error);
    if (!on_error && socket.is_open()) on_error = std::move(handler);
  }

  void deliver(size_t bytes) {
    if (!on_receive) return;
    ReceiveHandler handler = std::exchange(on_receive, nullptr);
    handler(std::span<const uint8_t>(buffer.data(), bytes), sender);
    if (!on_receive && socket.is_open()) on_receive = std::move(handler);
  }
};

Result<UdpEndpoint> UdpEndpoint::open(asio::io_context& io, std::string_view address,
                                      uint16_t port) {
  std::error_code ec;
  const asio::ip::address ip = asio::ip::make_address(std::string(address), ec);
  if (ec) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "udp: bad address '" + std::string(address) + "': " + ec.message());
  }
  auto state = std::make_shared<State>(io);
  const Endpoint endpoint(ip, port);
  state->socket.open(endpoint.protocol(), ec);
  if (!ec) state->socket.bind(endpoint, ec);
  // Sends must never stall the tick loop: a full buffer drops the datagram.
  if (!ec) state->socket.non_blocking(true, ec);
  if (!ec) state->local = state->socket.local_endpoint(ec);
  if (ec) {
    return Status::Error(ErrorCode::kIo, "udp: cannot bind " + std::string(address) + ":" +
                                             std::to_string(port) + ": " + ec.message());
  }
  return UdpEndpoint(std::move(state));
}

UdpEndpoint::UdpEndpoint(std::shared_ptr<State> state) : state_(std::move(state)) {}

UdpEndpoint& UdpEndpoint::operator=(UdpEndpoint&& other) noexcept {
  if (this != &other) {
    close();
    state_ = std::move(other.state_);
  }
  return *this;
}

UdpEndpoint::~UdpEndpoint() {
  close();
}

void UdpEndpoint::start_receiving(ReceiveHandler handler) {
  if (!state_ || !state_->socket.is_open()) return;
  state_->on_receive = std::move(handler);
  if (!state_->receiving) {
    state_->receiving = true;
    receive_next(state_);
  }
}

void UdpEndpoint::receive_next(const std::shared_ptr<State>& state) {
  state->socket.async_receive_from(
      asio::buffer(state->buffer), state->sender, [state](const std::error_code& ec, size_t bytes) {
        if (ec == asio::error::operation_aborted || !state->socket.is_open()) {
          state->receiving = false;
          return;
        }
        if (ec) {
          // ICMP port-unreachable surfaces here as connection_refused on some
          // platforms; the socket itself is fine, so keep listening.
          ++state->stats.receive_errors;
          state->report("receive", ec);
        } else {
          ++state->stats.datagrams_received;
          state->stats.bytes_received += bytes;
          state->deliver(bytes);
        }
        // The handler may have closed the endpoint.
        if (state->socket.is_open()) {
          receive_next(state);
        } else {
          state->receiving = false;
        }
      });
}

bool UdpEndpoint::send_to(std::span<const uint8_t> bytes, const Endpoint& to) {
  if (!state_ || !state_->socket.is_open()) return false;
  std::error_code ec;
  const size_t sent = state_->socket.send_to(asio::buffer(bytes.data(), bytes.size()), to, 0, ec);
  if (ec || sent != bytes.size()) {
    ++state_->stats.send_errors;
    state_->report("send", ec ? ec : std::make_error_code(std::errc::message_size));
    return false;
  }
  ++state_->stats.datagrams_sent;
  state_->stats.bytes_sent += bytes.size();
  return true;
}

void UdpEndpoint::close() {
  if (!state_) return;
  // Drop the user's handlers first: the aborted receive completes later
  // and must not call back into an owner that may be gone.
  state_->on_receive = nullptr;
  state_->on_error = nullptr;
  std::error_code ignored;
  state_->socket.close(ignored);
}

bool UdpEndpoint::is_open() const {
  return state_ && state_->socket.is_open();
}

void UdpEndpoint::set_error_handler(ErrorHandler handler) {
  if (state_) state_->on_error = std::move(handler);
}

UdpEndpoint::Endpoint UdpEndpoint::local_endpoint() const {
  return state_ ? state_->local : Endpoint{};
}

const UdpEndpoint::Stats& UdpEndpoint::stats() const {
  static const Stats kEmpty;
  return state_ ? state_->stats : kEmpty;
}

}  // namespace rwd::net
