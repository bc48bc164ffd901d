// SPDX-License-Identifier: MIT
// The client protocol on a UDP socket (or a caller's sender): everything
// here is transport; the protocol itself is in client_protocol.cpp.
#include "rewind/client/client_session.h"

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>
#include <optional>
#include <random>

#include "rewind/net/fault_injector.h"
#include "rewind/net/udp_endpoint.h"

namespace rwd::client {

struct ClientSession::Socket {
  net::UdpEndpoint endpoint;
  asio::ip::udp::endpoint server;
  std::optional<net::FaultyLink> outbound_faults;
  std::optional<net::FaultyLink> inbound_faults;

  void send(std::span<const uint8_t> datagram) {
    if (outbound_faults) {
      outbound_faults->send(datagram, server);
    } else {
      endpoint.send_to(datagram, server);
    }
  }
};

namespace {

/// Answers to one join are told from answers to another by this.
uint64_t random_join_nonce() {
  std::random_device device;
  return (uint64_t{device()} << 32) | device();
}

}  // namespace

Result<std::unique_ptr<ClientSession>> ClientSession::create(asio::io_context& io,
                                                             const ClientConfig& config) {
  std::error_code error;
  const asio::ip::address address = asio::ip::make_address(config.server_address, error);
  if (error) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "bad server address '" + config.server_address + "': " + error.message());
  }
  if (config.faults) {
    if (Status status = net::validate_fault_config(*config.faults); !status.ok()) return status;
  }
  Result<ClientProtocol> protocol = ClientProtocol::create(config, random_join_nonce());
  if (!protocol.ok()) return protocol.status();
  auto endpoint = net::UdpEndpoint::open(io, address.is_v6() ? "::" : "0.0.0.0", 0);
  if (!endpoint.ok()) return endpoint.status();

  std::unique_ptr<ClientSession> session(new ClientSession(std::move(*protocol), nullptr));
  session->socket_ = std::make_unique<Socket>(
      Socket{std::move(*endpoint), asio::ip::udp::endpoint(address, config.server_port), {}, {}});
  Socket& socket = *session->socket_;
  ClientSession* self = session.get();
  if (config.faults) {
    // Both directions see the configured conditions, with independent streams.
    net::FaultConfig out = *config.faults;
    net::FaultConfig in = *config.faults;
    in.seed = out.seed ^ 0xA5A5A5A5DEADBEEFull;
    socket.outbound_faults.emplace(std::move(*net::FaultyLink::create(
        io, out, [&socket](std::span<const uint8_t> bytes, const asio::ip::udp::endpoint& to) {
          socket.endpoint.send_to(bytes, to);
        })));
    socket.inbound_faults.emplace(std::move(*net::FaultyLink::create(
        io, in, [self](std::span<const uint8_t> bytes, const asio::ip::udp::endpoint& from) {
          self->on_socket_datagram(bytes, from == self->socket_->server);
        })));
  }
  socket.endpoint.start_receiving(
      [self](std::span<const uint8_t> bytes, const asio::ip::udp::endpoint& from) {
        if (self->socket_->inbound_faults) {
          self->socket_->inbound_faults->send(bytes, from);
        } else {
          self->on_socket_datagram(bytes, from == self->socket_->server);
        }
      });
  return session;
}

Result<std::unique_ptr<ClientSession>> ClientSession::create_detached(const ClientConfig& config,
                                                                      SendFn send) {
  if (config.faults) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "network faults are injected on a socket; a detached session has none");
  }
  if (!send) return Status::Error(ErrorCode::kInvalidArgument, "a detached session needs a sender");
  Result<ClientProtocol> protocol = ClientProtocol::create(config, random_join_nonce());
  if (!protocol.ok()) return protocol.status();
  return std::unique_ptr<ClientSession>(new ClientSession(std::move(*protocol), std::move(send)));
}

ClientSession::ClientSession(ClientProtocol protocol, SendFn send)
    : protocol_(std::move(protocol)), send_(std::move(send)) {}

ClientSession::~ClientSession() {
  // Close first so no receive handler can reach a half-destroyed session;
  // the fault links drop what they still hold when destroyed.
  if (socket_) socket_->endpoint.close();
}

void ClientSession::on_socket_datagram(std::span<const uint8_t> bytes, bool from_server) {
  if (!from_server) {
    ++foreign_datagrams_;
    return;
  }
  receive(bytes, net::SteadyClock::now());
}

void ClientSession::receive(std::span<const uint8_t> datagram, TimePoint now) {
  protocol_.receive(datagram, now);
  flush();
}

void ClientSession::connect(TimePoint now) {
  protocol_.connect(now);
  flush();
}

int ClientSession::update(TimePoint now) {
  const int stepped = protocol_.update(now);
  flush();
  return stepped;
}

void ClientSession::disconnect(const std::string& reason, TimePoint now) {
  protocol_.disconnect(reason, now);
  flush();
}

ClientStats ClientSession::stats() const {
  ClientStats out = protocol_.stats();
  out.packets_received += foreign_datagrams_;
  out.packets_rejected += foreign_datagrams_;
  return out;
}

uint16_t ClientSession::local_port() const {
  return socket_ ? socket_->endpoint.local_port() : 0;
}

void ClientSession::flush() {
  while (std::optional<std::span<const uint8_t>> datagram = protocol_.next_datagram()) {
    if (send_) {
      send_(*datagram);
    } else {
      socket_->send(*datagram);
    }
  }
}

}  // namespace rwd::client
