// SPDX-License-Identifier: MIT
#include "tls_context.h"

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

}  // namespace rwd::server
