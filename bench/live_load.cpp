// SPDX-License-Identifier: MIT
#include "live_load.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <thread>
#include <vector>

#include "rewind/net/connect_token.h"
#include "rewind/server/server.h"
#include "scripted_peer.h"

#if defined(__linux__)
#include <arpa/inet.h>
#include <netinet/in.h>
#include <pthread.h>
#include <sys/socket.h>
#include <unistd.h>
#endif

namespace rwd::bench {
namespace {

using Clock = std::chrono::steady_clock;

#if defined(__linux__)

double process_cpu_seconds() {
  timespec t{};
  if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t) != 0) return 0.0;
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) / 1e9;
}

double thread_cpu_seconds(pthread_t thread) {
  clockid_t clock = 0;
  timespec t{};
  if (pthread_getcpuclockid(thread, &clock) != 0 || clock_gettime(clock, &t) != 0) return 0.0;
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) / 1e9;
}

// Peer i sends from 127.1.0.0 + i + 1 (every 127/8 address is the
// loopback's), so one socket bound to the wildcard address speaks for all.
uint32_t peer_address(size_t i) {
  return 0x7F010000u + static_cast<uint32_t>(i) + 1;
}

// The peers' one socket: receives for every peer address (IP_PKTINFO says
// which), sends from any of them, a batch a system call each way.
class PeerSocket {
 public:
  static constexpr size_t kBatch = 64;
  static constexpr size_t kMaxDatagram = 2048;

  ~PeerSocket() {
    if (fd_ >= 0) ::close(fd_);
  }

  Status open() {
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd_ < 0) return Status::Error(ErrorCode::kIo, "peers: no socket");
    const int on = 1;
    // A hundred matches answer at once: room for every datagram of a tick.
    const int buffer = 32 << 20;
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUFFORCE, &buffer, sizeof buffer);
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &buffer, sizeof buffer);
    ::setsockopt(fd_, SOL_SOCKET, SO_SNDBUF, &buffer, sizeof buffer);
    sockaddr_in any{};
    any.sin_family = AF_INET;
    any.sin_addr.s_addr = htonl(INADDR_ANY);
    if (::setsockopt(fd_, IPPROTO_IP, IP_PKTINFO, &on, sizeof on) != 0 ||
        ::bind(fd_, reinterpret_cast<const sockaddr*>(&any), sizeof any) != 0) {
      return Status::Error(ErrorCode::kIo, "peers: cannot bind the peers' socket");
    }
    socklen_t length = sizeof any;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&any), &length);
    port_ = ntohs(any.sin_port);
    receive_.resize(kBatch * kMaxDatagram);
    return Status::Ok();
  }

  // Calls handler(peer address, bytes) for every datagram waiting.
  template <typename Handler>
  void drain(const Handler& handler) {
    mmsghdr messages[kBatch];
    iovec vectors[kBatch];
    alignas(cmsghdr) char control[kBatch][CMSG_SPACE(sizeof(in_pktinfo))];
    for (;;) {
      for (size_t i = 0; i < kBatch; ++i) {
        vectors[i] = {receive_.data() + i * kMaxDatagram, kMaxDatagram};
        std::memset(&messages[i], 0, sizeof messages[i]);
        messages[i].msg_hdr.msg_iov = &vectors[i];
        messages[i].msg_hdr.msg_iovlen = 1;
        messages[i].msg_hdr.msg_control = control[i];
        messages[i].msg_hdr.msg_controllen = sizeof control[i];
      }
      const int got = ::recvmmsg(fd_, messages, kBatch, MSG_DONTWAIT, nullptr);
      if (got <= 0) return;
      for (int i = 0; i < got; ++i) {
        for (cmsghdr* c = CMSG_FIRSTHDR(&messages[i].msg_hdr); c != nullptr;
             c = CMSG_NXTHDR(&messages[i].msg_hdr, c)) {
          if (c->cmsg_level != IPPROTO_IP || c->cmsg_type != IP_PKTINFO) continue;
          in_pktinfo info;
          std::memcpy(&info, CMSG_DATA(c), sizeof info);
          handler(ntohl(info.ipi_addr.s_addr),
                  std::span<const uint8_t>(static_cast<const uint8_t*>(vectors[i].iov_base),
                                           messages[i].msg_len));
        }
      }
      if (static_cast<size_t>(got) < kBatch) return;
    }
  }

  void queue(uint32_t from, const sockaddr_in& to, std::span<const uint8_t> bytes) {
    queued_.push_back({from, to, bytes_.size(), bytes.size()});
    bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
  }

  void flush() {
    size_t next = 0;
    mmsghdr messages[kBatch];
    iovec vectors[kBatch];
    alignas(cmsghdr) char control[kBatch][CMSG_SPACE(sizeof(in_pktinfo))];
    while (next < queued_.size()) {
      const size_t count = std::min(kBatch, queued_.size() - next);
      for (size_t i = 0; i < count; ++i) {
        Queued& q = queued_[next + i];
        vectors[i] = {bytes_.data() + q.offset, q.size};
        std::memset(&messages[i], 0, sizeof messages[i]);
        std::memset(control[i], 0, sizeof control[i]);
        messages[i].msg_hdr.msg_iov = &vectors[i];
        messages[i].msg_hdr.msg_iovlen = 1;
        messages[i].msg_hdr.msg_name = &q.to;
        messages[i].msg_hdr.msg_namelen = sizeof q.to;
        messages[i].msg_hdr.msg_control = control[i];
        messages[i].msg_hdr.msg_controllen = sizeof control[i];
        cmsghdr* c = CMSG_FIRSTHDR(&messages[i].msg_hdr);
        c->cmsg_level = IPPROTO_IP;
        c->cmsg_type = IP_PKTINFO;
        c->cmsg_len = CMSG_LEN(sizeof(in_pktinfo));
        in_pktinfo info{};
        info.ipi_spec_dst.s_addr = htonl(q.from);
        std::memcpy(CMSG_DATA(c), &info, sizeof info);
      }
      const int sent = ::sendmmsg(fd_, messages, static_cast<unsigned>(count), 0);
      next += sent > 0 ? static_cast<size_t>(sent) : 1;  // a refused one is lost, as UDP may
    }
    queued_.clear();
    bytes_.clear();
  }

  uint16_t port() const { return port_; }

 private:
  struct Queued {
    uint32_t from;
    sockaddr_in to;
    size_t offset;
    size_t size;
  };
  int fd_ = -1;
  uint16_t port_ = 0;
  std::vector<uint8_t> receive_;
  std::vector<uint8_t> bytes_;
  std::vector<Queued> queued_;
};

#endif

}  // namespace

#if defined(__linux__)

struct LiveLoad::Impl {
  LiveLoadConfig config;
  std::unique_ptr<server::Server> server;
  std::thread server_thread;
  PeerSocket socket;
  std::vector<std::unique_ptr<test::SecurePeer>> peers;  // match by match, slot by slot
  std::vector<sockaddr_in> server_of;                    // each peer's match's address
  std::thread peers_thread;
  std::atomic<bool> stopping{false};

  void run_peers() {
    const auto step = std::chrono::nanoseconds(1'000'000'000LL / config.tick_rate_hz) / 2;
    const uint32_t first = peer_address(0);
    net::TimePoint next = Clock::now();
    for (auto& peer : peers) peer->start(next);
    while (!stopping.load(std::memory_order_relaxed)) {
      const net::TimePoint now = Clock::now();
      socket.drain([&](uint32_t to, std::span<const uint8_t> bytes) {
        const uint32_t index = to - first;
        if (to >= first && index < peers.size()) peers[index]->receive(bytes, now);
      });
      for (auto& peer : peers) peer->update(now);
      socket.flush();
      next += step;
      if (next < now) next = now;
      std::this_thread::sleep_until(next);
    }
  }

  struct Totals {
    uint64_t ticks = 0, late = 0, missed = 0, bytes_out = 0;
    std::vector<uint64_t> lateness;  // bucket counts
    bool running = true;
  };
  Totals totals() const {
    Totals t;
    for (const server::MetricsSample& s : server->samples()) {
      t.ticks += s.tick_time.count();
      t.late += s.stats.ticks_late;
      t.missed += s.stats.ticks_missed;
      t.bytes_out += s.stats.bytes_out;
      t.running =
          t.running && s.phase == server::MatchHost::Phase::kRunning && s.stats.ticks_final > 0;
      t.lateness.resize(s.tick_lateness.bucket_total());
      for (size_t b = 0; b < s.tick_lateness.bucket_total(); ++b) {
        t.lateness[b] += s.tick_lateness.bucket_count(b);
      }
    }
    return t;
  }
};

Result<std::unique_ptr<LiveLoad>> LiveLoad::start(const LiveLoadConfig& config) {
  auto impl = std::make_unique<Impl>();
  impl->config = config;
  if (Status status = impl->socket.open(); !status.ok()) return status;

  server::ServerConfig server_config;
  server_config.match.game = config.game;
  server_config.match.players = config.players;
  server_config.match.max_spectators = 0;
  server_config.match.tick_rate_hz = config.tick_rate_hz;
  server_config.match.match_id = "live";
  server_config.match.join_timeout_s = 120;
  server_config.match.keyframe_interval = 0;
  server_config.bind_address = "127.0.0.1";
  server_config.port = 0;
  server_config.matches = config.matches;
  server_config.max_matches = std::max(1u, config.matches);
  server_config.threads = config.threads;
  server_config.server_key = net::generate_key();
  auto server = server::Server::create(server_config);
  if (!server.ok()) return server.status();
  impl->server = std::move(*server);

  const std::vector<uint16_t> ports = impl->server->ports();
  const int64_t now_unix = std::chrono::duration_cast<std::chrono::seconds>(
                               std::chrono::system_clock::now().time_since_epoch())
                               .count();
  Impl* self = impl.get();
  for (uint32_t m = 0; m < config.matches; ++m) {
    const std::string id = config.matches == 1 ? "live" : "live-" + std::to_string(m + 1);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    to.sin_port = htons(ports[m]);
    for (uint32_t slot = 0; slot < config.players; ++slot) {
      auto token = net::make_connect_token(*server_config.server_key, id, slot, slot + 1,
                                           now_unix + 6 * 3600, now_unix);
      if (!token.ok()) return token.status();
      const size_t index = impl->peers.size();
      test::ScriptedPeer::Settings settings;
      settings.game = config.game;
      settings.name = "peer-" + std::to_string(index);
      settings.nonce = index + 1;
      // Inputs that change as often as a stick does (cf. the host bench).
      settings.inputs = [](uint32_t player, Tick tick) {
        static constexpr int16_t kAxis[8] = {1000, 707, 0, -707, -1000, -707, 0, 707};
        const uint32_t phase = (static_cast<uint32_t>(tick) / 15 + player) % 8;
        return rwd::stick_input(kAxis[phase], kAxis[(phase + 2) % 8]);
      };
      settings.lead_ticks = 3.0;
      settings.period = std::chrono::nanoseconds(1'000'000'000LL / config.tick_rate_hz);
      impl->server_of.push_back(to);
      impl->peers.push_back(std::make_unique<test::SecurePeer>(
          *token, std::move(settings), [self, index](std::span<const uint8_t> bytes) {
            self->socket.queue(peer_address(index), self->server_of[index], bytes);
          }));
    }
  }
  impl->server_thread = std::thread([self] { self->server->run(); });
  impl->peers_thread = std::thread([self] { self->run_peers(); });
  return std::make_unique<LiveLoad>(std::move(impl));
}

LiveLoad::LiveLoad(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

LiveLoad::~LiveLoad() {
  impl_->server->shutdown("benchmark over");
  if (impl_->server_thread.joinable()) impl_->server_thread.join();
  impl_->stopping.store(true);
  if (impl_->peers_thread.joinable()) impl_->peers_thread.join();
}

bool LiveLoad::wait_running(std::chrono::seconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while (Clock::now() < deadline) {
    if (impl_->totals().running) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

LiveLoadReport LiveLoad::measure(double seconds) {
  const Impl::Totals before = impl_->totals();
  // The server's own threads are not ours to name, so its CPU is the
  // process's less the peers' thread's and this one's (which reads the
  // totals and sleeps).
  const double process0 = process_cpu_seconds();
  const double self0 = thread_cpu_seconds(pthread_self());
  const double peers0 = thread_cpu_seconds(impl_->peers_thread.native_handle());
  const auto t0 = Clock::now();
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  const Impl::Totals after = impl_->totals();
  const double process1 = process_cpu_seconds();
  const double self1 = thread_cpu_seconds(pthread_self());
  const double peers1 = thread_cpu_seconds(impl_->peers_thread.native_handle());
  const auto t1 = Clock::now();

  LiveLoadReport r;
  r.seconds = std::chrono::duration<double>(t1 - t0).count();
  r.matches = impl_->config.matches;
  r.ticks = after.ticks - before.ticks;
  r.ticks_due =
      static_cast<uint64_t>(r.seconds * impl_->config.tick_rate_hz * impl_->config.matches);
  r.late = after.late - before.late;
  r.missed = after.missed - before.missed;
  r.bytes_out = after.bytes_out - before.bytes_out;
  r.server_cpu_s = std::max(0.0, (process1 - process0) - (peers1 - peers0) - (self1 - self0));
  r.peers_cpu_s = peers1 - peers0;
  uint64_t total = 0;
  for (size_t b = 0; b < after.lateness.size(); ++b) {
    total += after.lateness[b] - (b < before.lateness.size() ? before.lateness[b] : 0);
  }
  uint64_t seen = 0;
  const auto& bounds = server::TickHistogram::kLatenessBoundsNs;
  for (size_t b = 0; b < after.lateness.size() && total > 0; ++b) {
    seen += after.lateness[b] - (b < before.lateness.size() ? before.lateness[b] : 0);
    if (seen * 100 >= total * 99) {
      r.lateness_p99_s = b < bounds.size() ? static_cast<double>(bounds[b]) / 1e9 : INFINITY;
      break;
    }
  }
  return r;
}

#else

struct LiveLoad::Impl {};

Result<std::unique_ptr<LiveLoad>> LiveLoad::start(const LiveLoadConfig&) {
  return Status::Error(ErrorCode::kInvalidArgument, "live load: Linux only (IP_PKTINFO peers)");
}
LiveLoad::LiveLoad(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
LiveLoad::~LiveLoad() = default;
bool LiveLoad::wait_running(std::chrono::seconds) {
  return false;
}
LiveLoadReport LiveLoad::measure(double) {
  return {};
}

#endif

}  // namespace rwd::bench
