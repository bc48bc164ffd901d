// SPDX-License-Identifier: MIT
#include "rewind/server/metrics_http.h"

#include <array>
#include <asio/buffer.hpp>
#include <asio/error.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/read_until.hpp>
#include <asio/steady_timer.hpp>
#include <asio/write.hpp>
#include <unordered_set>
#include <utility>

namespace rwd::server {
namespace {

constexpr std::string_view kHeadEnd = "\r\n\r\n";
constexpr std::string_view kMetricsPath = "/metrics";
constexpr std::string_view kBusy =
    "HTTP/1.1 503 Service Unavailable\r\nContent-Length: 0\r\nConnection: close\r\n\r\n";
// After an accept error (out of file descriptors, say) the next accept
// would fail at once again: wait instead of spinning next to the tick loop.
constexpr std::chrono::milliseconds kAcceptRetry{100};

std::string reply(std::string_view status, std::string_view content_type, std::string_view body,
                  bool with_body) {
  std::string out = "HTTP/1.1 ";
  out.append(status).append("\r\nContent-Type: ").append(content_type);
  out.append("\r\nContent-Length: ").append(std::to_string(body.size()));
  out.append("\r\nConnection: close\r\n\r\n");
  if (with_body) out.append(body);
  return out;
}

std::string bad_request() {
  return reply("400 Bad Request", "text/plain; charset=utf-8", "bad request\n", true);
}

bool is_upper_word(std::string_view text) {
  if (text.empty()) return false;
  for (const char c : text) {
    if (c < 'A' || c > 'Z') return false;
  }
  return true;
}

// Visible ASCII only: no spaces or control characters in a target.
bool is_visible(std::string_view text) {
  for (const char c : text) {
    if (c <= 0x20 || c >= 0x7f) return false;
  }
  return true;
}

// "Name: value", the name a visible word without the colon, the value free
// of control characters but tabs.
bool is_header_line(std::string_view line) {
  const size_t colon = line.find(':');
  if (colon == 0 || colon == std::string_view::npos) return false;
  if (!is_visible(line.substr(0, colon))) return false;
  for (const char c : line.substr(colon + 1)) {
    if ((c < 0x20 && c != '\t') || c == 0x7f) return false;
  }
  return true;
}

}  // namespace

struct MetricsHttp::State {
  State(const asio::any_io_executor& executor, RenderFn render_fn, RouteFn route_fn, Limits given)
      : acceptor(executor),
        retry(executor),
        render(std::move(render_fn)),
        route(std::move(route_fn)),
        limits(given) {}

  asio::ip::tcp::acceptor acceptor;
  asio::steady_timer retry;
  RenderFn render;
  RouteFn route;
  Limits limits;
  Stats stats;
  bool open = true;
  std::unordered_set<Connection*> live;  // so close() can reach every one
};

// One accepted socket: read the head, answer, then read and discard until
// the client closes, so closing never resets a connection whose answer is
// still on its way. The deadline closes it whatever state it is in.
class MetricsHttp::Connection : public std::enable_shared_from_this<Connection> {
 public:
  Connection(std::shared_ptr<State> state, asio::ip::tcp::socket socket)
      : state_(std::move(state)), socket_(std::move(socket)), deadline_(socket_.get_executor()) {
    state_->live.insert(this);
  }
  ~Connection() { state_->live.erase(this); }
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  void start() {
    deadline_.expires_after(state_->limits.deadline);
    deadline_.async_wait([self = shared_from_this()](const std::error_code& error) {
      if (error) return;  // cancelled: the connection ended in time
      if (!self->answered_) ++self->state_->stats.timed_out;
      self->stop();
    });
    asio::async_read_until(
        socket_, asio::dynamic_buffer(head_, state_->limits.max_header_bytes), kHeadEnd,
        [self = shared_from_this()](const std::error_code& error, size_t length) {
          self->on_head(error, length);
        });
  }

  void stop() {
    std::error_code ignored;
    socket_.close(ignored);
    deadline_.cancel();
  }

 private:
  void on_head(const std::error_code& error, size_t length) {
    if (!state_->open || error == asio::error::operation_aborted) return;
    // not_found: the limit was reached without the blank line. A client
    // that closes midway sent a malformed request too; one that sent
    // nothing gets nothing.
    if (error == asio::error::not_found || (error == asio::error::eof && !head_.empty())) {
      ++state_->stats.bad_requests;
      answer(bad_request());
      return;
    }
    if (error) {
      stop();
      return;
    }
    std::string response =
        respond(std::string_view(head_).substr(0, length), state_->render, state_->route);
    if (response.starts_with("HTTP/1.1 2")) {
      ++state_->stats.answered;
    } else if (response.starts_with("HTTP/1.1 404")) {
      ++state_->stats.not_found;
    } else {
      ++state_->stats.bad_requests;
    }
    answer(std::move(response));
  }

  void answer(std::string response) {
    answered_ = true;
    response_ = std::move(response);
    asio::async_write(socket_, asio::buffer(response_),
                      [self = shared_from_this()](const std::error_code& error, size_t) {
                        if (error || !self->state_->open) {
                          self->stop();
                          return;
                        }
                        std::error_code ignored;
                        self->socket_.shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
                        self->drain();
                      });
  }

  void drain() {
    socket_.async_read_some(asio::buffer(discard_),
                            [self = shared_from_this()](const std::error_code& error, size_t) {
                              if (error || !self->state_->open) {
                                self->stop();
                              } else {
                                self->drain();
                              }
                            });
  }

  std::shared_ptr<State> state_;
  asio::ip::tcp::socket socket_;
  asio::steady_timer deadline_;
  std::string head_;
  std::string response_;
  std::array<char, 512> discard_{};
  bool answered_ = false;
};

Result<std::unique_ptr<MetricsHttp>> MetricsHttp::open(asio::io_context& io,
                                                       std::string_view address, uint16_t port,
                                                       RenderFn render, Limits limits,
                                                       RouteFn route) {
  return open(io.get_executor(), address, port, std::move(render), limits, std::move(route));
}

Result<std::unique_ptr<MetricsHttp>> MetricsHttp::open(const asio::any_io_executor& executor,
                                                       std::string_view address, uint16_t port,
                                                       RenderFn render, Limits limits,
                                                       RouteFn route) {
  std::error_code ec;
  const asio::ip::address ip = asio::ip::make_address(std::string(address), ec);
  if (ec) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "metrics: bad address '" + std::string(address) + "': " + ec.message());
  }
  auto state = std::make_shared<State>(executor, std::move(render), std::move(route), limits);
  const asio::ip::tcp::endpoint endpoint(ip, port);
  state->acceptor.open(endpoint.protocol(), ec);
  if (!ec) state->acceptor.set_option(asio::ip::tcp::acceptor::reuse_address(true), ec);
  if (!ec) state->acceptor.bind(endpoint, ec);
  if (!ec) state->acceptor.listen(asio::socket_base::max_listen_connections, ec);
  const uint16_t bound = ec ? 0 : state->acceptor.local_endpoint(ec).port();
  if (ec) {
    return Status::Error(ErrorCode::kIo, "metrics: cannot listen on " + std::string(address) + ":" +
                                             std::to_string(port) + ": " + ec.message());
  }
  accept_next(state);
  return std::unique_ptr<MetricsHttp>(new MetricsHttp(std::move(state), bound));
}

MetricsHttp::MetricsHttp(std::shared_ptr<State> state, uint16_t port)
    : state_(std::move(state)), port_(port) {}

MetricsHttp::~MetricsHttp() {
  close();
}

void MetricsHttp::close() {
  if (!state_->open) return;
  state_->open = false;
  std::error_code ignored;
  state_->acceptor.close(ignored);
  state_->retry.cancel();
  // Copied: a connection leaves the set when its last handler lets it go.
  const std::unordered_set<Connection*> live = state_->live;
  for (Connection* connection : live) connection->stop();
}

const MetricsHttp::Stats& MetricsHttp::stats() const {
  return state_->stats;
}

void MetricsHttp::accept_next(const std::shared_ptr<State>& state) {
  state->acceptor.async_accept([state](const std::error_code& error, asio::ip::tcp::socket socket) {
    if (!state->open) return;
    if (error) {
      state->retry.expires_after(kAcceptRetry);
      state->retry.async_wait([state](const std::error_code& waited) {
        if (!waited && state->open) accept_next(state);
      });
      return;
    }
    if (state->live.size() >= state->limits.max_connections) {
      ++state->stats.busy;
      // A fresh socket's send buffer is empty, so this short write does not
      // block; whatever happens, the socket is closed.
      std::error_code ignored;
      socket.non_blocking(true, ignored);
      socket.write_some(asio::buffer(kBusy), ignored);
      socket.close(ignored);
    } else {
      std::make_shared<Connection>(state, std::move(socket))->start();
    }
    accept_next(state);
  });
}

std::string MetricsHttp::respond(std::string_view head, const RenderFn& render,
                                 const RouteFn& route) {
  if (!head.ends_with(kHeadEnd)) return bad_request();
  // Request line: METHOD SP TARGET SP HTTP/1.x
  const size_t line_end = head.find("\r\n");
  const std::string_view line = head.substr(0, line_end);
  const size_t first_space = line.find(' ');
  const size_t second_space =
      first_space == std::string_view::npos ? first_space : line.find(' ', first_space + 1);
  if (second_space == std::string_view::npos) return bad_request();
  const std::string_view method = line.substr(0, first_space);
  const std::string_view target = line.substr(first_space + 1, second_space - first_space - 1);
  const std::string_view version = line.substr(second_space + 1);
  if (!is_upper_word(method) || target.empty() || target.front() != '/' || !is_visible(target) ||
      (version != "HTTP/1.1" && version != "HTTP/1.0")) {
    return bad_request();
  }
  // Headers are checked for form only; none changes the answer.
  std::string_view rest = head.substr(line_end + 2, head.size() - line_end - 2 - 2);
  while (!rest.empty()) {
    const size_t end = rest.find("\r\n");
    if (!is_header_line(rest.substr(0, end))) return bad_request();
    rest.remove_prefix(end + 2);
  }
  const std::string_view path = target.substr(0, target.find('?'));
  if (path != kMetricsPath && route) {
    if (std::optional<HttpAnswer> answer = route(method, target)) {
      return reply(answer->status, answer->content_type, answer->body, method != "HEAD");
    }
  }
  if (path != kMetricsPath || (method != "GET" && method != "HEAD")) {
    return reply("404 Not Found", "text/plain; charset=utf-8", "not found\n", method != "HEAD");
  }
  return reply("200 OK", "text/plain; version=0.0.4", render(), method != "HEAD");
}

}  // namespace rwd::server
