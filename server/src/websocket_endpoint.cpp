// SPDX-License-Identifier: MIT
#include "rewind/server/websocket_endpoint.h"

#include <pthread.h>
#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/parser.hpp>
#include <boost/beast/http/read.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/http/write.hpp>
#include <boost/beast/ssl/ssl_stream.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <deque>
#include <list>
#include <mutex>
#include <thread>
#include <type_traits>

#include "endpoint_common.h"
#include "rewind/net/polled_udp_socket.h"
#include "rewind/server/server_log.h"

namespace rwd::server {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
using error_code = boost::system::error_code;

constexpr std::chrono::milliseconds kAcceptRetry{100};
constexpr uint32_t kMaxRequestHead = 8 * 1024;
// The subprotocol a browser may ask for (new WebSocket(url, "rewind")).
constexpr std::string_view kSubprotocol = "rewind";
constexpr std::string_view kMatchesPrefix = "/matches/";

// "duel-7" from "/matches/duel-7"; empty when the target is anything else.
std::string_view match_id_of(std::string_view target) {
  target = target.substr(0, target.find('?'));
  if (target.substr(0, kMatchesPrefix.size()) != kMatchesPrefix) return {};
  const std::string_view id = target.substr(kMatchesPrefix.size());
  return id.find('/') == std::string_view::npos ? id : std::string_view();
}

bool offers_subprotocol(std::string_view offered) {
  while (!offered.empty()) {
    const size_t comma = offered.find(',');
    std::string_view token = offered.substr(0, comma);
    while (!token.empty() && token.front() == ' ') token.remove_prefix(1);
    while (!token.empty() && token.back() == ' ') token.remove_suffix(1);
    if (token == kSubprotocol) return true;
    if (comma == std::string_view::npos) break;
    offered.remove_prefix(comma + 1);
  }
  return false;
}

}  // namespace

class SessionBase;

struct WebSocketEndpoint::Impl : std::enable_shared_from_this<WebSocketEndpoint::Impl> {
  Impl(FindPort find_port, Limits given)
      : acceptor(io), retry(io), find(std::move(find_port)), limits(given) {}

  void accept_next();
  void on_accept(const error_code& error, tcp::socket socket);
  void shut_down();

  asio::io_context io{1};
  tcp::acceptor acceptor;
  asio::steady_timer retry;
  FindPort find;
  Limits limits;
  std::optional<asio::ssl::context> tls;
  std::thread thread;
  bool serving = true;  // on the endpoint's thread
  std::atomic<bool> closed{false};
  // Open sessions. A session may end on a match's thread (the last
  // reference to it can be a match's, once the endpoint has closed): hence
  // the lock.
  std::mutex live_mutex;
  std::list<SessionBase*> live;

  std::atomic<uint64_t> upgraded{0}, not_found{0}, not_upgrade{0}, busy{0}, tls_failures{0},
      timed_out{0}, refused{0}, dropped_out{0}, bytes_in{0}, bytes_out{0};
};

// What the endpoint needs of a session to shut down, whatever its stream.
class SessionBase {
 public:
  explicit SessionBase(WebSocketEndpoint::Impl& endpoint) : endpoint_(endpoint) {
    std::lock_guard lock(endpoint_.live_mutex);
    position_ = endpoint_.live.insert(endpoint_.live.end(), this);
  }
  virtual ~SessionBase() {
    std::lock_guard lock(endpoint_.live_mutex);
    endpoint_.live.erase(position_);
  }
  SessionBase(const SessionBase&) = delete;
  SessionBase& operator=(const SessionBase&) = delete;
  virtual void stop() = 0;

 protected:
  WebSocketEndpoint::Impl& endpoint_;

 private:
  std::list<SessionBase*>::iterator position_;
};

// One browser: (a TLS handshake,) the HTTP upgrade request, checked and
// routed to its match, then binary messages both ways until either side
// closes. Everything but send() and close() runs on the endpoint's thread.
template <class Stream>
class Session final : public SessionBase,
                      public WebSocketPeer,
                      public std::enable_shared_from_this<Session<Stream>> {
 public:
  static constexpr bool kTls = !std::is_same_v<Stream, beast::tcp_stream>;

  Session(std::shared_ptr<WebSocketEndpoint::Impl> owner, tcp::socket socket)
      : SessionBase(*owner),
        owner_(std::move(owner)),
        ws_(make_stream(*owner_, std::move(socket))) {}

  void start() {
    beast::get_lowest_layer(ws_).expires_after(endpoint_.limits.handshake);
    if constexpr (kTls) {
      ws_.next_layer().async_handshake(
          asio::ssl::stream_base::server,
          [self = this->shared_from_this()](const error_code& error) { self->on_tls(error); });
    } else {
      read_request();
    }
  }

  void stop() override {
    error_code ignored;
    tcp::socket& socket = beast::get_lowest_layer(ws_).socket();
    socket.shutdown(tcp::socket::shutdown_both, ignored);
    socket.close(ignored);
  }

  // --- WebSocketPeer: called by the match, from any thread ---

  void send(std::vector<uint8_t> message) override {
    if (owner_->closed.load(std::memory_order_acquire)) return;
    asio::post(owner_->io, [self = this->shared_from_this(), m = std::move(message)]() mutable {
      self->enqueue(std::move(m));
    });
  }

  void close() override {
    if (owner_->closed.load(std::memory_order_acquire)) return;
    asio::post(owner_->io, [self = this->shared_from_this()] {
      self->closing_ = true;
      if (!self->writing_) self->close_now();
    });
  }

 private:
  static websocket::stream<Stream> make_stream(WebSocketEndpoint::Impl& endpoint,
                                               tcp::socket socket) {
    if constexpr (kTls) {
      return websocket::stream<Stream>(beast::tcp_stream(std::move(socket)), *endpoint.tls);
    } else {
      (void)endpoint;
      return websocket::stream<Stream>(std::move(socket));
    }
  }

  void on_tls(const error_code& error) {
    if (!endpoint_.serving || error == asio::error::operation_aborted) return;
    if (error == beast::error::timeout) {
      ++endpoint_.timed_out;
      return;
    }
    if (error) {
      ++endpoint_.tls_failures;
      return stop();
    }
    read_request();
  }

  void read_request() {
    parser_.header_limit(kMaxRequestHead);
    parser_.body_limit(0);
    http::async_read(ws_.next_layer(), buffer_, parser_,
                     [self = this->shared_from_this()](const error_code& error, size_t) {
                       self->on_request(error);
                     });
  }

  void on_request(const error_code& error) {
    if (!endpoint_.serving || error == asio::error::operation_aborted) return;
    if (error == beast::error::timeout) {
      ++endpoint_.timed_out;
      return;
    }
    if (error == http::error::end_of_stream || error == asio::error::eof) return;
    if (error) return reject(http::status::bad_request, "bad request\n");
    const auto& request = parser_.get();
    if (!websocket::is_upgrade(request)) {
      return reject(http::status::upgrade_required,
                    "this is Rewind's WebSocket endpoint: open ws://HOST:PORT/matches/<match id> "
                    "from a WebSocket client\n");
    }
    const std::string_view id = match_id_of(request.target());
    port_ = id.empty() ? nullptr : endpoint_.find(id);
    if (!port_) {
      ++endpoint_.not_found;
      return reject(http::status::not_found,
                    id.empty() ? std::string("expected /matches/<match id>\n")
                               : "no match '" + std::string(id) + "' takes browsers here\n");
    }
    const bool subprotocol = offers_subprotocol(request[http::field::sec_websocket_protocol]);
    ws_.set_option(websocket::stream_base::decorator([subprotocol](websocket::response_type& r) {
      if (subprotocol) r.set(http::field::sec_websocket_protocol, kSubprotocol);
    }));
    // From here on the WebSocket layer keeps time: pings when idle, and
    // the connection closed when nothing comes back.
    beast::get_lowest_layer(ws_).expires_never();
    websocket::stream_base::timeout timeout;
    timeout.handshake_timeout = endpoint_.limits.handshake;
    timeout.idle_timeout = endpoint_.limits.idle;
    timeout.keep_alive_pings = true;
    ws_.set_option(timeout);
    ws_.binary(true);
    ws_.read_message_max(net::PolledUdpSocket::kMaxDatagram);
    ws_.async_accept(request, [self = this->shared_from_this()](const error_code& accepted) {
      self->on_accept(accepted);
    });
  }

  void reject(http::status status, std::string body) {
    if (status != http::status::not_found) ++endpoint_.not_upgrade;
    response_.result(status);
    response_.version(11);
    response_.set(http::field::content_type, "text/plain; charset=utf-8");
    response_.keep_alive(false);
    response_.body() = std::move(body);
    response_.prepare_payload();
    http::async_write(
        ws_.next_layer(), response_,
        [self = this->shared_from_this()](const error_code&, size_t) { self->stop(); });
  }

  void on_accept(const error_code& error) {
    if (!endpoint_.serving || error) {
      if (error == beast::error::timeout) ++endpoint_.timed_out;
      return;
    }
    error_code ignored;
    const tcp::endpoint peer = beast::get_lowest_layer(ws_).socket().remote_endpoint(ignored);
    auto attached = port_->attach(this->shared_from_this(), peer.port());
    if (!attached.ok()) {
      ++endpoint_.not_found;
      ws_.async_close(websocket::close_reason(websocket::close_code::try_again_later,
                                              attached.status().message()),
                      [self = this->shared_from_this()](const error_code&) {});
      return;
    }
    self_endpoint_ = *attached;
    attached_ = true;
    ++endpoint_.upgraded;
    write_log(LogLevel::kInfo, "websocket: " + peer.address().to_string() + ":" +
                                   std::to_string(peer.port()) + " is [" +
                                   self_endpoint_.address().to_string() +
                                   "]:" + std::to_string(self_endpoint_.port()) + " in its match");
    read();
  }

  void read() {
    ws_.async_read(incoming_, [self = this->shared_from_this()](const error_code& error, size_t) {
      self->on_read(error);
    });
  }

  void on_read(const error_code& error) {
    if (error) {
      if (error == beast::error::timeout) ++endpoint_.timed_out;
      if (error == websocket::error::message_too_big) ++endpoint_.refused;
      return detach();
    }
    if (!ws_.got_binary()) {
      // A text message is no datagram: the client is not speaking Rewind.
      ++endpoint_.refused;
      detach();
      closing_ = true;
      if (!writing_) close_now();
      return;
    }
    const auto data = incoming_.cdata();
    endpoint_.bytes_in += data.size();
    port_->deliver(self_endpoint_,
                   std::span<const uint8_t>(static_cast<const uint8_t*>(data.data()), data.size()));
    incoming_.consume(incoming_.size());
    if (endpoint_.serving) {
      read();
    } else {
      detach();  // closing: no read will end with an error to do it
    }
  }

  void detach() {
    if (!attached_) return;
    attached_ = false;
    port_->detach(self_endpoint_);
  }

  void enqueue(std::vector<uint8_t> message) {
    if (closing_ || !endpoint_.serving) return;
    if (queued_bytes_ + message.size() > endpoint_.limits.max_queued_bytes) {
      ++endpoint_.dropped_out;
      return;
    }
    queued_bytes_ += message.size();
    outgoing_.push_back(std::move(message));
    if (!writing_) write_next();
  }

  void write_next() {
    if (outgoing_.empty()) {
      writing_ = false;
      if (closing_) close_now();
      return;
    }
    writing_ = true;
    ws_.async_write(asio::buffer(outgoing_.front()),
                    [self = this->shared_from_this()](const error_code& error, size_t written) {
                      self->on_written(error, written);
                    });
  }

  void on_written(const error_code& error, size_t written) {
    queued_bytes_ -= outgoing_.front().size();
    outgoing_.pop_front();
    if (error) {
      writing_ = false;
      outgoing_.clear();
      queued_bytes_ = 0;
      return;  // the read side sees the same failure and detaches
    }
    endpoint_.bytes_out += written;
    write_next();
  }

  void close_now() {
    if (close_sent_ || !ws_.is_open()) return;
    close_sent_ = true;
    ws_.async_close(websocket::close_code::normal,
                    [self = this->shared_from_this()](const error_code&) {});
  }

  std::shared_ptr<WebSocketEndpoint::Impl> owner_;  // keeps the io_context alive
  websocket::stream<Stream> ws_;
  beast::flat_buffer buffer_;
  http::request_parser<http::empty_body> parser_;
  http::response<http::string_body> response_;
  beast::flat_buffer incoming_;
  std::shared_ptr<WebSocketPort> port_;
  WebSocketPort::Endpoint self_endpoint_;
  bool attached_ = false;
  std::deque<std::vector<uint8_t>> outgoing_;
  size_t queued_bytes_ = 0;
  bool writing_ = false;
  bool closing_ = false;
  bool close_sent_ = false;
};

void WebSocketEndpoint::Impl::accept_next() {
  acceptor.async_accept(
      [this](const error_code& error, tcp::socket socket) { on_accept(error, std::move(socket)); });
}

void WebSocketEndpoint::Impl::on_accept(const error_code& error, tcp::socket socket) {
  if (!serving) return;
  if (error) {
    retry.expires_after(kAcceptRetry);
    retry.async_wait([this](const error_code& waited) {
      if (!waited && serving) accept_next();
    });
    return;
  }
  size_t open = 0;
  {
    std::lock_guard lock(live_mutex);
    open = live.size();
  }
  if (open >= limits.max_connections) {
    ++busy;
    refuse_busy(socket);
  } else {
    // The sessions share this endpoint's ownership: a match may hold one
    // (its port does) for a moment after the endpoint has closed.
    std::shared_ptr<Impl> self = shared_from_this();
    if (tls) {
      std::make_shared<Session<beast::ssl_stream<beast::tcp_stream>>>(self, std::move(socket))
          ->start();
    } else {
      std::make_shared<Session<beast::tcp_stream>>(self, std::move(socket))->start();
    }
  }
  accept_next();
}

void WebSocketEndpoint::Impl::shut_down() {
  serving = false;
  error_code ignored;
  acceptor.close(ignored);
  retry.cancel();
  std::lock_guard lock(live_mutex);
  for (SessionBase* session : live) session->stop();
}

Result<std::unique_ptr<WebSocketEndpoint>> WebSocketEndpoint::open(
    std::string_view address, uint16_t port, FindPort find, Limits limits,
    const std::optional<HttpTls>& tls) {
  const std::string prefix = "websocket";
  if (limits.max_connections == 0 || limits.max_queued_bytes < net::PolledUdpSocket::kMaxDatagram ||
      limits.handshake.count() <= 0 || limits.idle.count() <= 0) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         prefix + ": limits must be positive, and the queue hold a datagram");
  }
  auto impl = std::make_shared<Impl>(std::move(find), limits);
  if (tls) {
    auto context = tls_server_context(prefix, *tls);
    if (!context.ok()) return context.status();
    impl->tls.emplace(std::move(*context));
  }
  auto bound = listen_on(impl->acceptor, prefix, address, port);
  if (!bound.ok()) return bound.status();
  impl->accept_next();
  Impl* raw = impl.get();
  impl->thread = std::thread([raw] {
    // Named, so operators (top -H) and the browser test see its CPU apart.
    pthread_setname_np(pthread_self(), "rewind-ws");
    raw->io.run();
  });
  std::unique_ptr<WebSocketEndpoint> out(new WebSocketEndpoint(std::move(impl)));
  out->port_ = *bound;
  return out;
}

WebSocketEndpoint::WebSocketEndpoint(std::shared_ptr<Impl> impl) : impl_(std::move(impl)) {}

WebSocketEndpoint::~WebSocketEndpoint() {
  close();
}

void WebSocketEndpoint::close() {
  if (impl_->closed.exchange(true)) return;
  // Every operation ends with operation_aborted, each session detaches from
  // its match and drops its last reference, and run() returns once nothing
  // is pending.
  asio::post(impl_->io, [impl = impl_.get()] { impl->shut_down(); });
  impl_->thread.join();
}

WebSocketEndpoint::Stats WebSocketEndpoint::stats() const {
  Stats out;
  out.upgraded = impl_->upgraded.load();
  out.not_found = impl_->not_found.load();
  out.not_upgrade = impl_->not_upgrade.load();
  out.busy = impl_->busy.load();
  out.tls_failures = impl_->tls_failures.load();
  out.timed_out = impl_->timed_out.load();
  out.refused = impl_->refused.load();
  out.dropped_out = impl_->dropped_out.load();
  out.bytes_in = impl_->bytes_in.load();
  out.bytes_out = impl_->bytes_out.load();
  return out;
}

}  // namespace rwd::server
