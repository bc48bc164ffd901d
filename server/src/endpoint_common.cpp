// SPDX-License-Identifier: MIT
#include "endpoint_common.h"

namespace rwd::server {

namespace asio = boost::asio;
using error_code = boost::system::error_code;

Result<asio::ssl::context> tls_server_context(const std::string& prefix, const HttpTls& tls) {
  asio::ssl::context context(asio::ssl::context::tls_server);
  context.set_options(asio::ssl::context::default_workarounds | asio::ssl::context::no_sslv2 |
                      asio::ssl::context::no_sslv3 | asio::ssl::context::no_tlsv1 |
                      asio::ssl::context::no_tlsv1_1);
  const auto fail = [&](const std::string& what, const std::string& file, const error_code& e) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         prefix + ": TLS " + what + " " + file + ": " + e.message());
  };
  error_code error;
  context.use_certificate_chain_file(tls.certificate_file, error);
  if (error) return fail("certificate", tls.certificate_file, error);
  context.use_private_key_file(tls.private_key_file, asio::ssl::context::pem, error);
  if (error) return fail("private key", tls.private_key_file, error);
  if (!tls.client_ca_file.empty()) {
    context.load_verify_file(tls.client_ca_file, error);
    if (error) return fail("client CA", tls.client_ca_file, error);
    context.set_verify_mode(asio::ssl::verify_peer | asio::ssl::verify_fail_if_no_peer_cert, error);
    if (error) return fail("client CA", tls.client_ca_file, error);
  }
  return context;
}

Result<uint16_t> listen_on(asio::ip::tcp::acceptor& acceptor, const std::string& prefix,
                           std::string_view address, uint16_t port) {
  error_code error;
  const asio::ip::address ip = asio::ip::make_address(std::string(address), error);
  if (error) {
    return Status::Error(
        ErrorCode::kInvalidArgument,
        prefix + ": bad address '" + std::string(address) + "': " + error.message());
  }
  const asio::ip::tcp::endpoint endpoint(ip, port);
  acceptor.open(endpoint.protocol(), error);
  if (!error) acceptor.set_option(asio::ip::tcp::acceptor::reuse_address(true), error);
  if (!error) acceptor.bind(endpoint, error);
  if (!error) acceptor.listen(asio::socket_base::max_listen_connections, error);
  const uint16_t bound = error ? 0 : acceptor.local_endpoint(error).port();
  if (error) {
    return Status::Error(ErrorCode::kIo, prefix + ": cannot listen on " + std::string(address) +
                                             ":" + std::to_string(port) + ": " + error.message());
  }
  return bound;
}

void refuse_busy(asio::ip::tcp::socket& socket) {
  static constexpr std::string_view kBusy =
      "HTTP/1.1 503 Service Unavailable\r\nContent-Length: 0\r\nConnection: close\r\n\r\n";
  error_code ignored;
  socket.non_blocking(true, ignored);
  socket.write_some(asio::buffer(kBusy.data(), kBusy.size()), ignored);
  socket.close(ignored);
}

}  // namespace rwd::server
