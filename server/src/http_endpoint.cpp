// SPDX-License-Identifier: MIT
#include "rewind/server/http_endpoint.h"

#include "endpoint_common.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/error.hpp>
#include <boost/beast/http/parser.hpp>
#include <boost/beast/http/read.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/http/write.hpp>
#include <boost/beast/ssl/ssl_stream.hpp>
#include <exception>
#include <list>
#include <optional>
#include <thread>
#include <type_traits>

namespace rwd::server {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;
using error_code = boost::system::error_code;

// After an accept error (out of file descriptors, say) the next accept
// would fail at once again: wait instead of spinning.
constexpr std::chrono::milliseconds kAcceptRetry{100};

using RequestParser = http::request_parser<http::string_body>;

void limit(RequestParser& parser, const HttpEndpointLimits& limits) {
  parser.header_limit(static_cast<uint32_t>(std::min<size_t>(limits.max_header_bytes, UINT32_MAX)));
  parser.body_limit(limits.max_body_bytes);
}

HttpRequest request_of(const http::request<http::string_body>& message) {
  HttpRequest request;
  request.method = std::string(message.method_string());
  request.target = std::string(message.target());
  request.authorization = std::string(message[http::field::authorization]);
  request.body = message.body();
  return request;
}

}  // namespace

Result<HttpRequest> parse_http_request(std::string_view bytes, const HttpEndpointLimits& limits) {
  RequestParser parser;
  limit(parser, limits);
  parser.eager(true);
  error_code error;
  size_t used = 0;
  while (!error && used < bytes.size() && !parser.is_done()) {
    const size_t taken = parser.put(asio::buffer(bytes.data() + used, bytes.size() - used), error);
    used += taken;
    if (error == http::error::need_more || taken == 0) break;
  }
  if (!error && !parser.is_done()) {
    // Nothing at all is no request; otherwise the end of the bytes ends a
    // body that runs to the end, or leaves the message short.
    if (!parser.got_some()) {
      return Status::Error(ErrorCode::kCorrupt, "not an HTTP request: no bytes");
    }
    parser.put_eof(error);
  }
  if (error == http::error::header_limit) {
    return Status::Error(ErrorCode::kCapacity, "request head too large");
  }
  if (error == http::error::body_limit) {
    return Status::Error(ErrorCode::kCapacity, "request body too large");
  }
  if (error || !parser.is_done()) {
    return Status::Error(ErrorCode::kCorrupt,
                         "not an HTTP request: " + (error ? error.message() : "incomplete"));
  }
  HttpRequest request = request_of(parser.get());
  if (request.target.empty() || request.target.front() != '/') {
    return Status::Error(ErrorCode::kCorrupt, "not an HTTP request: the target is not a path");
  }
  return request;
}

std::string_view HttpRequest::path() const {
  return std::string_view(target).substr(0, target.find('?'));
}

std::string_view HttpRequest::query() const {
  const size_t question = target.find('?');
  return question == std::string::npos ? std::string_view()
                                       : std::string_view(target).substr(question + 1);
}

bool is_loopback_address(std::string_view address) {
  error_code error;
  const asio::ip::address ip = asio::ip::make_address(std::string(address), error);
  if (error) return false;
  if (ip.is_loopback()) return true;
  return ip.is_v6() && ip.to_v6().is_v4_mapped() &&
         asio::ip::make_address_v4(asio::ip::v4_mapped, ip.to_v6()).is_loopback();
}

class ConnectionBase;

struct HttpEndpoint::Impl {
  Impl(std::string endpoint_name, Handler handler_fn, Limits given)
      : acceptor(io),
        retry(io),
        name(std::move(endpoint_name)),
        handler(std::move(handler_fn)),
        limits(given) {}

  void accept_next();
  void on_accept(const error_code& error, tcp::socket socket);
  /// Makes room for one more connection; false when none can give way.
  bool make_room();
  void shut_down();

  asio::io_context io{1};
  tcp::acceptor acceptor;
  asio::steady_timer retry;
  std::string name;
  Handler handler;
  Limits limits;
  std::optional<asio::ssl::context> tls;  // set: every connection is TLS
  std::thread thread;
  bool serving = true;  // on the endpoint's thread
  std::atomic<bool> closed{false};
  // Open connections, oldest first; each removes itself when it ends.
  std::list<ConnectionBase*> live;
  size_t evicting = 0;  // connections closed for room whose handlers are still pending

  std::atomic<uint64_t> answered{0}, refused{0}, bad_requests{0}, timed_out{0}, evicted{0}, busy{0},
      tls_failures{0};
};

// What the endpoint needs of a connection, whatever its stream.
class ConnectionBase {
 public:
  enum class Phase : uint8_t { kReading, kAnswering, kDraining };

  explicit ConnectionBase(HttpEndpoint::Impl& endpoint) : endpoint_(endpoint) {
    position_ = endpoint_.live.insert(endpoint_.live.end(), this);
  }
  virtual ~ConnectionBase() {
    if (evicted_) --endpoint_.evicting;
    endpoint_.live.erase(position_);
  }
  ConnectionBase(const ConnectionBase&) = delete;
  ConnectionBase& operator=(const ConnectionBase&) = delete;

  Phase phase() const { return phase_; }
  bool evicted() const { return evicted_; }

  // Closes the socket for a newer connection: the pending operation ends
  // with operation_aborted and the last reference goes with it.
  void evict() {
    evicted_ = true;
    ++endpoint_.evicting;
    ++endpoint_.evicted;
    stop();
  }
  virtual void stop() = 0;

 protected:
  HttpEndpoint::Impl& endpoint_;
  Phase phase_ = Phase::kReading;

 private:
  std::list<ConnectionBase*>::iterator position_;
  bool evicted_ = false;
};

// One accepted socket: (a TLS handshake,) read one request, answer it, then
// end the connection: a plain one reads and discards until the client
// closes (so closing never resets a connection whose answer is still on
// its way), a TLS one sends its close_notify. The deadline, set once at
// accept, ends it whatever it is doing. A TLS handshake counts as waiting
// for the request.
template <class Stream>
class HttpConnection final : public ConnectionBase,
                             public std::enable_shared_from_this<HttpConnection<Stream>> {
 public:
  static constexpr bool kTls = !std::is_same_v<Stream, beast::tcp_stream>;

  HttpConnection(HttpEndpoint::Impl& endpoint, tcp::socket socket)
      : ConnectionBase(endpoint), stream_(make_stream(endpoint, std::move(socket))) {}

  void start() {
    beast::get_lowest_layer(stream_).expires_after(endpoint_.limits.deadline);
    if constexpr (kTls) {
      stream_.async_handshake(asio::ssl::stream_base::server,
                              [self = this->shared_from_this()](const error_code& error) {
                                self->on_handshake(error);
                              });
    } else {
      read();
    }
  }

  void stop() override {
    error_code ignored;
    tcp::socket& socket = beast::get_lowest_layer(stream_).socket();
    socket.shutdown(tcp::socket::shutdown_both, ignored);
    socket.close(ignored);
  }

 private:
  static Stream make_stream(HttpEndpoint::Impl& endpoint, tcp::socket socket) {
    if constexpr (kTls) {
      return Stream(beast::tcp_stream(std::move(socket)), *endpoint.tls);
    } else {
      (void)endpoint;
      return Stream(std::move(socket));
    }
  }

  void on_handshake(const error_code& error) {
    if (!endpoint_.serving || error == asio::error::operation_aborted) return;
    if (error == beast::error::timeout) {
      ++endpoint_.timed_out;
      return;
    }
    // No certificate, one the client CA did not sign, not TLS at all.
    if (error) {
      ++endpoint_.tls_failures;
      return stop();
    }
    read();
  }

  void read() {
    parser_.emplace();
    limit(*parser_, endpoint_.limits);
    http::async_read(stream_, buffer_, *parser_,
                     [self = this->shared_from_this()](const error_code& error, size_t) {
                       self->on_read(error);
                     });
  }

  void on_read(const error_code& error) {
    if (!endpoint_.serving || error == asio::error::operation_aborted) return;
    if (error == beast::error::timeout) {
      ++endpoint_.timed_out;
      return;
    }
    if (error == http::error::header_limit) return reject(431, "request head too large\n");
    if (error == http::error::body_limit) return reject(413, "request body too large\n");
    // A client that closes before sending anything asked for nothing.
    if (error == http::error::end_of_stream) return;
    if (error.category() == http::make_error_code(http::error::header_limit).category() ||
        error == asio::error::eof) {
      return reject(400, "bad request\n");
    }
    if (error) return;  // reset, broken pipe, a TLS alert: nobody to answer
    HttpRequest request = request_of(parser_->get());
    error_code ignored;
    const tcp::endpoint peer = beast::get_lowest_layer(stream_).socket().remote_endpoint(ignored);
    request.peer = peer.address().to_string();
    HttpReply reply;
    if (request.target.empty() || request.target.front() != '/') {
      return reject(400, "bad request\n");
    }
    try {
      reply = endpoint_.handler(request);
    } catch (const std::exception&) {
      reply = HttpReply{500, "text/plain; charset=utf-8", "internal error\n", {}};
    }
    ++(reply.status < 300 ? endpoint_.answered : endpoint_.refused);
    answer(std::move(reply), request.method == "HEAD");
  }

  void reject(unsigned status, std::string body) {
    ++endpoint_.bad_requests;
    answer(HttpReply{status, "text/plain; charset=utf-8", std::move(body), {}}, false);
  }

  void answer(HttpReply reply, bool head_only) {
    phase_ = Phase::kAnswering;
    response_.result(reply.status);
    response_.version(11);
    response_.set(http::field::content_type, reply.content_type);
    for (const auto& [field, value] : reply.headers) response_.set(field, value);
    response_.keep_alive(false);
    response_.body() = std::move(reply.body);
    response_.prepare_payload();
    if (head_only) response_.body().clear();  // Content-Length stays the GET's
    http::async_write(stream_, response_,
                      [self = this->shared_from_this()](const error_code& error, size_t) {
                        if (error || !self->endpoint_.serving) return self->stop();
                        self->finish();
                      });
  }

  void finish() {
    phase_ = Phase::kDraining;
    if constexpr (kTls) {
      stream_.async_shutdown(
          [self = this->shared_from_this()](const error_code&) { self->stop(); });
    } else {
      error_code ignored;
      stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
      drain();
    }
  }

  void drain() {
    stream_.async_read_some(asio::buffer(discard_),
                            [self = this->shared_from_this()](const error_code& error, size_t) {
                              if (error || !self->endpoint_.serving) return self->stop();
                              self->drain();
                            });
  }

  Stream stream_;
  beast::flat_buffer buffer_;
  std::optional<RequestParser> parser_;
  http::response<http::string_body> response_;
  std::array<char, 512> discard_{};
};

void HttpEndpoint::Impl::accept_next() {
  acceptor.async_accept(
      [this](const error_code& error, tcp::socket socket) { on_accept(error, std::move(socket)); });
}

void HttpEndpoint::Impl::on_accept(const error_code& error, tcp::socket socket) {
  if (!serving) return;
  if (error) {
    retry.expires_after(kAcceptRetry);
    retry.async_wait([this](const error_code& waited) {
      if (!waited && serving) accept_next();
    });
    return;
  }
  if (live.size() - evicting >= limits.max_connections && !make_room()) {
    ++busy;
    refuse_busy(socket);
  } else if (tls) {
    std::make_shared<HttpConnection<beast::ssl_stream<beast::tcp_stream>>>(*this, std::move(socket))
        ->start();
  } else {
    std::make_shared<HttpConnection<beast::tcp_stream>>(*this, std::move(socket))->start();
  }
  accept_next();
}

bool HttpEndpoint::Impl::make_room() {
  // A connection that is done and only draining goes first, then the one
  // that has waited longest for its request; one being answered stays.
  ConnectionBase* oldest_reading = nullptr;
  for (ConnectionBase* connection : live) {
    if (connection->evicted()) continue;
    if (connection->phase() == ConnectionBase::Phase::kDraining) {
      connection->evict();
      return true;
    }
    if (oldest_reading == nullptr && connection->phase() == ConnectionBase::Phase::kReading) {
      oldest_reading = connection;
    }
  }
  if (oldest_reading == nullptr) return false;
  oldest_reading->evict();
  return true;
}

void HttpEndpoint::Impl::shut_down() {
  serving = false;
  error_code ignored;
  acceptor.close(ignored);
  retry.cancel();
  for (ConnectionBase* connection : live) connection->stop();
}

Result<std::unique_ptr<HttpEndpoint>> HttpEndpoint::open(std::string_view name,
                                                         std::string_view address, uint16_t port,
                                                         Handler handler, Limits limits,
                                                         const std::optional<HttpTls>& tls) {
  const std::string prefix(name);
  if (limits.max_connections == 0) {
    return Status::Error(ErrorCode::kInvalidArgument, prefix + ": max connections must be > 0");
  }
  auto impl = std::make_unique<Impl>(prefix, std::move(handler), limits);
  if (tls) {
    auto context = tls_server_context(prefix, *tls);
    if (!context.ok()) return context.status();
    impl->tls.emplace(std::move(*context));
  }
  auto bound = listen_on(impl->acceptor, prefix, address, port);
  if (!bound.ok()) return bound.status();
  impl->accept_next();
  Impl* raw = impl.get();
  impl->thread = std::thread([raw] { raw->io.run(); });
  std::unique_ptr<HttpEndpoint> out(new HttpEndpoint(std::move(impl)));
  out->port_ = *bound;
  return out;
}

HttpEndpoint::HttpEndpoint(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

HttpEndpoint::~HttpEndpoint() {
  close();
}

void HttpEndpoint::close() {
  if (impl_->closed.exchange(true)) return;
  // Every operation ends with operation_aborted, its handler drops its
  // connection, and run() returns once nothing is pending.
  asio::post(impl_->io, [impl = impl_.get()] { impl->shut_down(); });
  impl_->thread.join();
}

HttpEndpoint::Stats HttpEndpoint::stats() const {
  Stats out;
  out.answered = impl_->answered.load();
  out.refused = impl_->refused.load();
  out.bad_requests = impl_->bad_requests.load();
  out.timed_out = impl_->timed_out.load();
  out.evicted = impl_->evicted.load();
  out.busy = impl_->busy.load();
  out.tls_failures = impl_->tls_failures.load();
  return out;
}

}  // namespace rwd::server
