// SPDX-License-Identifier: MIT
#include "rewind/client/websocket_link.h"

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/websocket.hpp>
#include <deque>
#include <vector>

namespace rwd::client {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
using error_code = boost::system::error_code;

constexpr std::string_view kScheme = "ws://";
// Larger than any datagram the server sends (PolledUdpSocket::kMaxDatagram).
constexpr size_t kMaxMessage = 2048;

struct Url {
  std::string host;
  std::string port;
  std::string target;
};

Result<Url> parse_url(std::string_view url) {
  const auto bad = [&](const std::string& why) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "WebSocket URL '" + std::string(url) + "': " + why);
  };
  if (url.substr(0, kScheme.size()) != kScheme) return bad("expected ws://HOST:PORT/PATH");
  std::string_view rest = url.substr(kScheme.size());
  const size_t slash = rest.find('/');
  std::string_view authority = rest.substr(0, slash);
  Url out;
  out.target = slash == std::string_view::npos ? "/" : std::string(rest.substr(slash));
  size_t colon;
  if (!authority.empty() && authority.front() == '[') {
    const size_t close = authority.find(']');
    if (close == std::string_view::npos) return bad("unclosed [ in the host");
    out.host = std::string(authority.substr(1, close - 1));
    colon = close + 1 < authority.size() && authority[close + 1] == ':' ? close + 1
                                                                        : std::string_view::npos;
  } else {
    colon = authority.rfind(':');
    out.host = std::string(authority.substr(0, colon));
  }
  if (out.host.empty()) return bad("no host");
  if (colon == std::string_view::npos) return bad("no port");
  out.port = std::string(authority.substr(colon + 1));
  if (out.port.empty() || out.port.size() > 5 ||
      out.port.find_first_not_of("0123456789") != std::string::npos || std::stoul(out.port) == 0 ||
      std::stoul(out.port) > 65535) {
    return bad("the port must be a number in [1, 65535]");
  }
  return out;
}

}  // namespace

struct WebSocketLink::Impl {
  explicit Impl(Url where) : url(std::move(where)), resolver(io), ws(io) {}

  void start() {
    resolver.async_resolve(
        url.host, url.port, [this](const error_code& error, tcp::resolver::results_type results) {
          if (error) return fail("cannot resolve " + url.host, error);
          beast::get_lowest_layer(ws).expires_after(std::chrono::seconds(10));
          beast::get_lowest_layer(ws).async_connect(
              results,
              [this](const error_code& connected, const tcp::endpoint&) { on_connect(connected); });
        });
  }

  void on_connect(const error_code& error) {
    if (error) return fail("cannot connect to " + url.host + ":" + url.port, error);
    beast::get_lowest_layer(ws).expires_never();
    ws.set_option(websocket::stream_base::timeout::suggested(beast::role_type::client));
    ws.binary(true);
    ws.read_message_max(kMaxMessage);
    ws.async_handshake(url.host + ":" + url.port, url.target, [this](const error_code& shaken) {
      if (shaken) return fail("the WebSocket handshake with " + url.target + " failed", shaken);
      state = State::kOpen;
      read();
      write_next();
    });
  }

  void read() {
    ws.async_read(incoming, [this](const error_code& error, size_t) {
      if (error) return fail("the connection ended", error);
      const auto data = incoming.cdata();
      ++stats.messages_in;
      stats.bytes_in += data.size();
      if (on_message) {
        (*on_message)(
            std::span<const uint8_t>(static_cast<const uint8_t*>(data.data()), data.size()));
      }
      ++delivered;
      incoming.consume(incoming.size());
      read();
    });
  }

  void write_next() {
    if (writing || state != State::kOpen || outgoing.empty()) return;
    writing = true;
    ws.async_write(asio::buffer(outgoing.front()), [this](const error_code& error, size_t n) {
      writing = false;
      if (error) return fail("sending failed", error);
      if (outgoing.empty()) return;  // cleared by a failure on the read side
      waiting_bytes -= outgoing.front().size();
      outgoing.pop_front();
      ++stats.messages_out;
      stats.bytes_out += n;
      write_next();
    });
  }

  void fail(const std::string& what, const error_code& error) {
    if (state == State::kClosed) return;
    state = State::kClosed;
    if (error_text.empty() && error != asio::error::operation_aborted) {
      error_text = what + ": " + error.message();
    }
    stats.dropped_out += outgoing.size();
    outgoing.clear();
    waiting_bytes = 0;
    error_code ignored;
    beast::get_lowest_layer(ws).socket().close(ignored);
  }

  Url url;
  asio::io_context io{1};
  tcp::resolver resolver;
  websocket::stream<beast::tcp_stream> ws;
  State state = State::kConnecting;
  std::string error_text;
  beast::flat_buffer incoming;
  std::deque<std::vector<uint8_t>> outgoing;
  size_t waiting_bytes = 0;
  bool writing = false;
  const MessageFn* on_message = nullptr;  // set during poll()
  size_t delivered = 0;
  Stats stats;
};

Result<std::unique_ptr<WebSocketLink>> WebSocketLink::open(std::string_view url) {
  auto parsed = parse_url(url);
  if (!parsed.ok()) return parsed.status();
  auto impl = std::make_unique<Impl>(std::move(*parsed));
  impl->start();
  return std::unique_ptr<WebSocketLink>(new WebSocketLink(std::move(impl)));
}

WebSocketLink::WebSocketLink(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

WebSocketLink::~WebSocketLink() {
  impl_->state = State::kClosed;
  impl_->io.stop();
}

void WebSocketLink::send(std::span<const uint8_t> datagram) {
  Impl& link = *impl_;
  if (link.state == State::kClosed) {
    ++link.stats.dropped_out;
    return;
  }
  link.outgoing.emplace_back(datagram.begin(), datagram.end());
  link.waiting_bytes += datagram.size();
  // Drop the oldest unsent datagrams past the limit; the one being written
  // (the front, while writing) stays.
  while (link.waiting_bytes > kMaxWaiting && link.outgoing.size() > (link.writing ? 2u : 1u)) {
    auto victim = link.outgoing.begin() + (link.writing ? 1 : 0);
    link.waiting_bytes -= victim->size();
    link.outgoing.erase(victim);
    ++link.stats.dropped_out;
  }
  link.write_next();
}

size_t WebSocketLink::poll(const MessageFn& on_message) {
  Impl& link = *impl_;
  link.on_message = &on_message;
  link.delivered = 0;
  if (link.io.stopped()) link.io.restart();
  link.io.poll();
  link.on_message = nullptr;
  return link.delivered;
}

void WebSocketLink::close() {
  Impl& link = *impl_;
  if (link.state != State::kOpen) {
    link.fail("closed", asio::error::operation_aborted);
    return;
  }
  link.state = State::kClosed;
  link.ws.async_close(websocket::close_code::normal, [](const error_code&) {});
  if (link.io.stopped()) link.io.restart();
  link.io.run_for(std::chrono::milliseconds(200));
}

WebSocketLink::State WebSocketLink::state() const {
  return impl_->state;
}
const std::string& WebSocketLink::error() const {
  return impl_->error_text;
}
WebSocketLink::Stats WebSocketLink::stats() const {
  return impl_->stats;
}

}  // namespace rwd::client
