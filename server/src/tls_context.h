// SPDX-License-Identifier: MIT
#pragma once
// The TLS settings every server endpoint shares (HTTP and WebSocket).
#include <boost/asio/ssl/context.hpp>
#include <string>

#include "rewind/core/status.h"
#include "rewind/server/http_endpoint.h"

namespace rwd::server {

/// TLS 1.2 and newer with the server's certificate; with a client CA,
/// mutual TLS: a client without a certificate that CA signed never gets to
/// send a request. Errors (kInvalidArgument) start with `prefix` and name
/// the file that could not be used.
Result<boost::asio::ssl::context> tls_server_context(const std::string& prefix, const HttpTls& tls);

}  // namespace rwd::server
