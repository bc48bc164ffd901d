// SPDX-License-Identifier: MIT
#include "headless_match.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <thread>

#include "rewind/core/splitmix64.h"
#include "rewind/game/crates_game.h"
#include "rewind/net/address_cookie.h"
#include "rewind/net/connect_token.h"
#include "rewind/net/connection.h"
#include "rewind/net/envelope_codec.h"
#include "scripted_peer.h"

namespace rwd::test {

using Clock = std::chrono::steady_clock;
using client::ClientEvent;
using client::ClientEventType;

class HeadlessMatch::Peer {
 public:
  virtual ~Peer() = default;
  virtual void start(TimePoint now) = 0;
  virtual void receive(std::span<const uint8_t> datagram, TimePoint now) = 0;
  virtual void update(TimePoint now) = 0;
  /// Has left the match (said goodbye, or given up).
  virtual bool done() const = 0;
};

namespace {

constexpr uint16_t kFirstPort = 20000;
// Connect tokens of secure matches live this long, from the real clock.
constexpr int64_t kTokenLifetimeS = 6 * 3600;

Clock::duration from_ms(double ms) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(ms));
}

// A real client SDK session with no socket.
class SdkPeer final : public HeadlessMatch::Peer {
 public:
  SdkPeer(std::unique_ptr<client::ClientSession> session, const InputScript& inputs)
      : session_(std::move(session)) {
    client::ClientSession* s = session_.get();
    if (inputs) {
      session_->set_input_provider([s, inputs](Tick tick) { return inputs(s->player(), tick); });
    }
  }
  void start(TimePoint now) override { session_->connect(now); }
  void receive(std::span<const uint8_t> datagram, TimePoint now) override {
    session_->receive(datagram, now);
  }
  void update(TimePoint now) override {
    session_->update(now);
    ClientEvent event;
    while (session_->poll_event(event)) {
      if (event.type == ClientEventType::kFinalTick) {
        ++result_.final_tick_events;
        continue;
      }
      if (event.type == ClientEventType::kMatchEnded) result_.ended = true;
      result_.events.push_back(event);
    }
  }
  bool done() const override { return session_->phase() == client::ClientSession::Phase::kEnded; }
  SdkClientResult result() const {
    SdkClientResult out = result_;
    out.player = session_->player();
    out.stats = session_->stats();
    return out;
  }

 private:
  std::unique_ptr<client::ClientSession> session_;
  SdkClientResult result_;
};

// The scripted peers, plain or secure, as headless peers.
template <typename Scripted>
class ScriptedAdapter final : public HeadlessMatch::Peer {
 public:
  template <typename... Args>
  explicit ScriptedAdapter(Args&&... args) : peer_(std::forward<Args>(args)...) {}
  void start(TimePoint now) override { peer_.start(now); }
  void receive(std::span<const uint8_t> datagram, TimePoint now) override {
    peer_.receive(datagram, now);
  }
  void update(TimePoint now) override { peer_.update(now); }
  bool done() const override { return peer_.done(); }

 private:
  Scripted peer_;
};

uint64_t mix(uint64_t z) {
  return splitmix64_once(z);
}

}  // namespace

uint64_t SdkClientResult::count(client::ClientEventType type) const {
  return static_cast<uint64_t>(std::count_if(
      events.begin(), events.end(), [type](const ClientEvent& e) { return e.type == type; }));
}

Result<std::unique_ptr<HeadlessMatch>> HeadlessMatch::create(const HeadlessConfig& config) {
  if (config.sdk_clients > config.match.players) {
    return Status::Error(ErrorCode::kInvalidArgument, "more SDK clients than player slots");
  }
  if (config.updates_per_tick < 1 || config.latency_ms < 0 || config.jitter_ms < 0 ||
      config.jitter_ms > config.latency_ms) {
    return Status::Error(ErrorCode::kInvalidArgument, "bad network or update settings");
  }
  auto match = std::make_unique<HeadlessMatch>(config, net::SteadyClock::now());
  HeadlessMatch* self = match.get();
  auto to_client = [self](const server::Endpoint& to, std::span<const uint8_t> bytes) {
    self->transmit(Direction::kToClient, static_cast<uint32_t>(to.port() - kFirstPort), bytes);
  };
  server::MatchConfig match_config = config.match;
  match_config.secure = config.secure;
  const net::Key server_key = net::generate_key();
  if (config.secure) {
    // The secure gateway sits between the network and the host as in the
    // server (MatchRunner): it answers handshakes, opens what arrives and
    // seals what the host sends.
    server::SecureGateway::Options options;
    options.slots = config.match.players + config.match.max_spectators;
    options.join_grace_s = static_cast<int64_t>(std::ceil(config.match.peer_timeout_s));
    options.seated = [self](uint32_t slot, const server::Endpoint& endpoint) {
      return self->host_->seated(slot, endpoint);
    };
    match->gateway_ = std::make_unique<server::SecureGateway>(server_key, config.match.match_id,
                                                              std::move(options), to_client);
  }
  auto host = server::MatchHost::create(
      match_config,
      [self, to_client](const server::Endpoint& to, std::span<const uint8_t> bytes) {
        if (self->gateway_) {
          self->gateway_->send(to, bytes);
        } else {
          to_client(to, bytes);
        }
      },
      self->now_);
  if (!host.ok()) return host.status();
  match->host_ = std::move(*host);
  if (!config.secure) {
    match->tokenless_ = std::make_unique<server::TokenlessGateway>(to_client);
  }

  const auto period =
      std::chrono::nanoseconds(1'000'000'000LL / static_cast<int64_t>(config.match.tick_rate_hz));
  const double period_ms = std::chrono::duration<double, std::milli>(period).count();
  // A scripted peer's inputs must reach the server before it needs them:
  // the server's clock is a one-way trip old when heard, the inputs take
  // another, and two ticks of margin cover jitter and the update step.
  const double lead_ticks = 2.0 * (config.latency_ms + config.jitter_ms) / period_ms + 2.0;
  const int64_t unix_now = self->unix_seconds(self->now_);
  for (uint32_t i = 0; i < config.match.players; ++i) {
    auto send = [self, i](std::span<const uint8_t> bytes) {
      self->transmit(Direction::kToServer, i, bytes);
    };
    std::optional<net::ConnectToken> token;
    if (config.secure) {
      auto minted = net::make_connect_token(server_key, config.match.match_id, i, i + 1,
                                            unix_now + kTokenLifetimeS, unix_now);
      if (!minted.ok()) return minted.status();
      token = *minted;
    }
    if (i < config.sdk_clients) {
      client::ClientConfig client_config;
      client_config.game = config.match.game;
      client_config.name = "sdk-" + std::to_string(i);
      client_config.snapshot_ticks = config.snapshot_ticks;
      if (static_cast<int32_t>(i) == config.corrupt_client) {
        client_config.debug_corrupt_at_tick = config.corrupt_at_tick;
      }
      if (token) client_config.connect_token = net::write_connect_token(*token);
      auto session = client::ClientSession::create_detached(client_config, send);
      if (!session.ok()) return session.status();
      match->peers_.push_back(std::make_unique<SdkPeer>(std::move(*session), config.inputs));
    } else {
      ScriptedPeer::Settings settings;
      settings.game = config.match.game;
      settings.name = "scripted-" + std::to_string(i);
      settings.nonce = mix(config.seed ^ mix(i));
      settings.inputs = config.inputs;
      settings.lead_ticks = lead_ticks;
      settings.period = period;
      if (token) {
        match->peers_.push_back(
            std::make_unique<ScriptedAdapter<SecurePeer>>(*token, std::move(settings), send));
      } else {
        match->peers_.push_back(
            std::make_unique<ScriptedAdapter<ScriptedPeer>>(std::move(settings), send));
      }
    }
  }
  return match;
}

HeadlessMatch::HeadlessMatch(const HeadlessConfig& config, TimePoint start)
    : config_(config),
      now_(start),
      start_(start),
      unix_start_s_(std::chrono::duration_cast<std::chrono::seconds>(
                        std::chrono::system_clock::now().time_since_epoch())
                        .count()),
      rng_(config.seed) {}

int64_t HeadlessMatch::unix_seconds(TimePoint at) const {
  return unix_start_s_ + std::chrono::duration_cast<std::chrono::seconds>(at - start_).count();
}

HeadlessMatch::~HeadlessMatch() = default;

server::Endpoint HeadlessMatch::endpoint_of(uint32_t peer) const {
  return server::Endpoint(asio::ip::address_v4::loopback(),
                          static_cast<uint16_t>(kFirstPort + peer));
}

void HeadlessMatch::transmit(Direction direction, uint32_t peer, std::span<const uint8_t> bytes) {
  if (peer >= peers_.size() && direction == Direction::kToClient) return;  // not one of ours
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  if (config_.loss > 0 && unit(rng_) < config_.loss) return;
  InFlight item;
  item.bytes.assign(bytes.begin(), bytes.end());
  if (filter_ && !filter_(direction, peer, item.bytes)) return;
  const double delay_ms = config_.latency_ms + config_.jitter_ms * (2.0 * unit(rng_) - 1.0);
  item.at = now_ + from_ms(delay_ms);
  item.order = next_order_++;
  item.direction = direction;
  item.peer = peer;
  if (direction == Direction::kToClient) ++datagrams_to_clients_;
  in_flight_.push(std::move(item));
}

void HeadlessMatch::deliver_due() {
  while (!in_flight_.empty() && in_flight_.top().at <= now_) {
    // Moving the bytes out leaves the ordering fields intact for pop().
    InFlight item = std::move(const_cast<InFlight&>(in_flight_.top()));
    in_flight_.pop();
    if (item.direction == Direction::kToServer) {
      const auto begin = std::chrono::steady_clock::now();
      const server::Endpoint from = endpoint_of(item.peer);
      if (gateway_) {
        gateway_->on_datagram(item.bytes, from, unix_seconds(item.at),
                              [&](std::span<const uint8_t> envelope, const server::Endpoint& sender,
                                  const server::Admission& who) {
                                host_->on_datagram(envelope, sender, item.at, &who);
                              });
      } else {
        tokenless_->on_datagram(item.bytes, from, item.at,
                                [&](std::span<const uint8_t> envelope,
                                    const server::Endpoint& sender, const server::Admission* who) {
                                  host_->on_datagram(envelope, sender, item.at, who);
                                });
      }
      host_busy_ += std::chrono::steady_clock::now() - begin;
    } else {
      peers_[item.peer]->receive(item.bytes, item.at);
    }
  }
}

HeadlessResult HeadlessMatch::run() {
  const auto period =
      std::chrono::nanoseconds(1'000'000'000LL / static_cast<int64_t>(config_.match.tick_rate_hz));
  const auto step = period / config_.updates_per_tick;
  const TimePoint start = now_;
  const TimePoint limit = start + from_ms(config_.max_match_seconds * 1000.0);
  HeadlessResult result;
  for (auto& peer : peers_) peer->start(now_);
  TimePoint next_tick = now_ + period;
  const auto wall_start = std::chrono::steady_clock::now();
  for (;;) {
    now_ += step;
    if (config_.wall_paced && now_ >= next_tick) {
      std::this_thread::sleep_until(wall_start + (next_tick - start));
    }
    deliver_due();
    if (now_ >= next_tick) {
      const auto begin = std::chrono::steady_clock::now();
      host_->on_tick(now_);
      host_busy_ += std::chrono::steady_clock::now() - begin;
      ++host_ticks_;
      host_tick_seconds_.push_back(
          std::chrono::duration<double>(host_busy_ - busy_before_).count());
      busy_before_ = host_busy_;
      next_tick += period;
    }
    bool all_done = host_->phase() == server::MatchHost::Phase::kEnded;
    for (auto& peer : peers_) {
      peer->update(now_);
      all_done = all_done && peer->done();
    }
    if (all_done) break;
    if (now_ >= limit) {
      result.timed_out = true;
      break;
    }
  }
  result.server = host_->stats();
  result.simulated_seconds = std::chrono::duration<double>(now_ - start).count();
  result.host_busy_seconds = std::chrono::duration<double>(host_busy_).count();
  result.host_ticks = host_ticks_;
  result.host_tick_seconds = std::move(host_tick_seconds_);
  result.datagrams_to_clients = datagrams_to_clients_;
  for (uint32_t i = 0; i < peers_.size(); ++i) {
    if (i < config_.sdk_clients) {
      result.clients.push_back(static_cast<const SdkPeer&>(*peers_[i]).result());
    } else if (peers_[i]->done()) {
      ++result.scripted_peers_finished;
    }
  }
  return result;
}

rwd::PlayerInput aggressive_crates_input(uint64_t seed, uint32_t player, Tick tick) {
  // Ten-second phases: four in five send everyone into the same corner,
  // the fifth is a free-for-all with a new direction every 45 ticks.
  const uint64_t phase = mix(seed ^ mix(static_cast<uint64_t>(tick) / 600));
  rwd::StickInput input;
  if (phase % 5 < 4) {
    input.axis_x = (phase & 1) ? rwd::kAxisMax : -rwd::kAxisMax;
    input.axis_y = (phase & 2) ? rwd::kAxisMax : -rwd::kAxisMax;
  } else {
    const uint64_t d =
        mix(phase ^ mix(player + 1) ^ mix(static_cast<uint64_t>(tick) / 45 + 0x5151));
    input.axis_x = static_cast<int16_t>(static_cast<int64_t>(d % 2001) - 1000);
    input.axis_y = static_cast<int16_t>(static_cast<int64_t>((d >> 16) % 2001) - 1000);
  }
  // Everyone jumps and dashes together, about as often as the cooldown
  // allows, so the pile keeps climbing over itself. Together, because each
  // press is a misprediction for every other client: staggered presses
  // would make the clients re-simulate several times over, for no more
  // chaos in the pile.
  if (tick % 37 == 0) input.buttons |= game::kCratesJump;
  if (tick % 67 == 0) input.buttons |= game::kCratesDash;
  return rwd::PlayerInput::of(input);
}

}  // namespace rwd::test
