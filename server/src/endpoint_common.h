// SPDX-License-Identifier: MIT
#pragma once
// What the server's TCP endpoints (HTTP and WebSocket) share: their TLS
// settings, how they listen, and how they turn a connection away.
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl/context.hpp>
#include <cstdint>
#include <string>
#include <string_view>

#include "rewind/core/status.h"
#include "rewind/server/http_endpoint.h"

namespace rwd::server {

/// TLS 1.2 and newer with the server's certificate; with a client CA,
/// mutual TLS: a client without a certificate that CA signed never gets to
/// send a request. Errors (kInvalidArgument) start with `prefix` and name
/// the file that could not be used.
Result<boost::asio::ssl::context> tls_server_context(const std::string& prefix, const HttpTls& tls);

/// Opens `acceptor` on `address` (an IPv4 or IPv6 literal) and `port` (0:
/// any free port) and listens; returns the bound port. kInvalidArgument for
/// a bad address, kIo when the OS refuses; messages start with `prefix`.
Result<uint16_t> listen_on(boost::asio::ip::tcp::acceptor& acceptor, const std::string& prefix,
                           std::string_view address, uint16_t port);

/// Answers a connection 503 and closes it: a fresh socket's send buffer is
/// empty, so the short write does not block; whatever happens, the socket
/// is closed.
void refuse_busy(boost::asio::ip::tcp::socket& socket);

}  // namespace rwd::server
