// SPDX-License-Identifier: MIT
#include "headless_match.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "rewind/game/crates_game.h"
#include "rewind/net/address_cookie.h"
#include "rewind/net/connection.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/proto/input_wire.h"

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

using SendFn = std::function<void(std::span<const uint8_t>)>;
constexpr uint16_t kFirstPort = 20000;
constexpr auto kJoinResend = std::chrono::milliseconds(250);
constexpr auto kEndingWait = std::chrono::milliseconds(1500);

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

// A protocol peer without a simulation: joins, sends its scripted inputs a
// little ahead of the server's clock (every unacknowledged one, in one
// frame), acknowledges the final ticks it got, leaves at the end.
class ScriptedPeer final : public HeadlessMatch::Peer {
 public:
  ScriptedPeer(const std::string& game, const std::string& name, uint64_t nonce, InputScript inputs,
               double lead_ticks, Clock::duration period, SendFn send)
      : game_(game),
        name_(name),
        nonce_(nonce),
        inputs_(std::move(inputs)),
        lead_ticks_(lead_ticks),
        period_(period),
        send_(std::move(send)),
        connection_(TimePoint{}) {}

  void start(TimePoint now) override {
    connection_ = net::Connection(now);
    joining_ = true;
    last_join_ = now - kJoinResend;
  }

  void receive(std::span<const uint8_t> datagram, TimePoint now) override {
    if (const std::optional<net::AddressCookie> cookie = net::read_cookie(datagram)) {
      if (joining_ && !cookie_) {
        cookie_ = *cookie;
        last_join_ = now - kJoinResend;  // the join goes out on the next update
      }
      return;
    }
    auto decoded = net::decode_envelope(datagram);
    if (!decoded.ok()) return;
    const v1::Envelope& e = *decoded;
    if (e.has_join_accept()) {
      if (!joining_ || e.join_accept().nonce() != nonce_) return;
      connection_.set_connection_id(e.join_accept().connection_id());
    }
    if (connection_.connection_id() == 0 || e.connection_id() != connection_.connection_id()) {
      return;
    }
    if (!connection_.on_receive(e, now).is_new()) return;
    switch (e.payload_case()) {
      case v1::Envelope::kJoinAccept:
        player_ = e.join_accept().player();
        joining_ = false;
        break;
      case v1::Envelope::kMatchStart:
        started_ = true;
        hear_server_tick(e.match_start().server_tick(), now);
        break;
      case v1::Envelope::kFinalTicks:
        on_final_ticks(e.final_ticks(), now);
        break;
      case v1::Envelope::kResyncChunk:
        // The server thinks we fell behind its history and restarts us from
        // a snapshot. Without a simulation there is nothing to load: take
        // the snapshot's tick as the new base, as a client would.
        if (e.resync_chunk().tick() - 1 > contiguous_) {
          contiguous_ = e.resync_chunk().tick() - 1;
          ahead_.erase(ahead_.begin(), ahead_.upper_bound(contiguous_));
        }
        break;
      case v1::Envelope::kMatchEnd:
        if (done_) {
          say_goodbye(now);  // our goodbye was lost: the server still waits
        } else if (!ending_) {
          ending_ = true;
          end_tick_ = e.match_end().last_final_tick();
          ending_deadline_ = now + kEndingWait;
        }
        break;
      case v1::Envelope::kDisconnect:
        done_ = true;
        break;
      default:
        break;  // relayed inputs and pongs: nothing to do without a simulation
    }
  }

  void update(TimePoint now) override {
    if (done_) return;
    if (joining_) {
      if (now - last_join_ >= kJoinResend) {
        last_join_ = now;
        if (!cookie_) {
          send_(net::make_hello());  // until the server's cookie comes back
          return;
        }
        v1::Envelope envelope;
        envelope.mutable_join_request()->set_game(game_);
        envelope.mutable_join_request()->set_client_name(name_);
        envelope.mutable_join_request()->set_nonce(nonce_);
        connection_.stamp(envelope, now);
        if (net::encode_envelope(envelope, buffer_).ok()) {
          net::frame_join(*cookie_, buffer_, framed_);
          send_(framed_);
        }
      }
      return;
    }
    if (!started_) return;
    if (ending_ && (contiguous_ >= end_tick_ || now >= ending_deadline_)) {
      say_goodbye(now);
      done_ = true;
      return;
    }
    if (sent_once_ && now - last_frame_ < period_) return;
    sent_once_ = true;
    last_frame_ = now;
    // Inputs up to where the server will be when they arrive, plus a margin.
    const double elapsed_ticks = std::chrono::duration<double>(now - heard_at_).count() /
                                 std::chrono::duration<double>(period_).count();
    const auto target = static_cast<Tick>(std::floor(server_tick_ + elapsed_ticks + lead_ticks_));
    const Tick first = std::max<Tick>(input_ack_ + 1, 0);
    v1::Envelope envelope;
    v1::InputFrame* frame = envelope.mutable_input_frame();
    frame->set_player(player_);
    frame->set_first_tick(first);
    frame->set_last_final_tick_seen(contiguous_);
    if (!ending_) {
      for (Tick t = first; t <= target && t < first + 64; ++t) {
        *frame->add_inputs() = proto::to_wire(inputs_ ? inputs_(player_, t) : game::PlayerInput{});
      }
    }
    send(envelope, now);
  }

  bool done() const override { return done_; }

 private:
  void hear_server_tick(int32_t tick, TimePoint now) {
    if (tick > server_tick_ || heard_at_ == TimePoint{}) {
      server_tick_ = tick;
      heard_at_ = now;
    }
  }

  void on_final_ticks(const v1::FinalTicks& finals, TimePoint now) {
    hear_server_tick(finals.server_tick(), now);
    input_ack_ = std::max(input_ack_, finals.input_ack_tick());
    for (const v1::FinalTick& f : finals.ticks()) {
      if (f.tick() <= contiguous_) continue;
      if (f.tick() > contiguous_ + 1) {
        ahead_.insert(f.tick());
        continue;
      }
      contiguous_ = f.tick();
      while (!ahead_.empty() && *ahead_.begin() <= contiguous_ + 1) {
        contiguous_ = std::max(contiguous_, *ahead_.begin());
        ahead_.erase(ahead_.begin());
      }
    }
  }

  void say_goodbye(TimePoint now) {
    v1::Envelope bye;
    bye.mutable_disconnect()->set_reason("match over");
    send(bye, now);
  }

  void send(v1::Envelope& envelope, TimePoint now) {
    connection_.stamp(envelope, now);
    if (net::encode_envelope(envelope, buffer_).ok()) send_(buffer_);
  }

  std::string game_;
  std::string name_;
  uint64_t nonce_;
  InputScript inputs_;
  double lead_ticks_;
  Clock::duration period_;
  SendFn send_;
  net::Connection connection_;
  std::vector<uint8_t> buffer_;
  std::vector<uint8_t> framed_;
  std::optional<net::AddressCookie> cookie_;  // the server's, for our join
  bool joining_ = false;
  bool started_ = false;
  bool ending_ = false;
  bool done_ = false;
  bool sent_once_ = false;
  uint32_t player_ = 0;
  TimePoint last_join_;
  TimePoint last_frame_;
  TimePoint heard_at_;
  TimePoint ending_deadline_;
  int32_t server_tick_ = 0;
  Tick input_ack_ = kNoTick;
  Tick contiguous_ = kNoTick;  // every final tick up to here was received
  Tick end_tick_ = kNoTick;
  std::set<Tick> ahead_;  // final ticks received beyond a gap
};

uint64_t mix(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
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
  auto host = server::MatchHost::create(
      config.match,
      [self](const server::Endpoint& to, std::span<const uint8_t> bytes) {
        self->transmit(Direction::kToClient, static_cast<uint32_t>(to.port() - kFirstPort), bytes);
      },
      self->now_);
  if (!host.ok()) return host.status();
  match->host_ = std::move(*host);
  match->gateway_ = std::make_unique<server::TokenlessGateway>(
      [self](const server::Endpoint& to, std::span<const uint8_t> bytes) {
        self->transmit(Direction::kToClient, static_cast<uint32_t>(to.port() - kFirstPort), bytes);
      });

  const auto period =
      std::chrono::nanoseconds(1'000'000'000LL / static_cast<int64_t>(config.match.tick_rate_hz));
  const double period_ms = std::chrono::duration<double, std::milli>(period).count();
  // A scripted peer's inputs must reach the server before it needs them:
  // the server's clock is a one-way trip old when heard, the inputs take
  // another, and two ticks of margin cover jitter and the update step.
  const double lead_ticks = 2.0 * (config.latency_ms + config.jitter_ms) / period_ms + 2.0;
  for (uint32_t i = 0; i < config.match.players; ++i) {
    auto send = [self, i](std::span<const uint8_t> bytes) {
      self->transmit(Direction::kToServer, i, bytes);
    };
    if (i < config.sdk_clients) {
      client::ClientConfig client_config;
      client_config.game = config.match.game;
      client_config.name = "sdk-" + std::to_string(i);
      client_config.snapshot_ticks = config.snapshot_ticks;
      if (static_cast<int32_t>(i) == config.corrupt_client) {
        client_config.debug_corrupt_at_tick = config.corrupt_at_tick;
      }
      auto session = client::ClientSession::create_detached(client_config, send);
      if (!session.ok()) return session.status();
      match->peers_.push_back(std::make_unique<SdkPeer>(std::move(*session), config.inputs));
    } else {
      match->peers_.push_back(std::make_unique<ScriptedPeer>(
          config.match.game, "scripted-" + std::to_string(i), mix(config.seed ^ mix(i)),
          config.inputs, lead_ticks, period, send));
    }
  }
  return match;
}

HeadlessMatch::HeadlessMatch(const HeadlessConfig& config, TimePoint start)
    : config_(config), now_(start), rng_(config.seed) {}

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
      gateway_->on_datagram(
          item.bytes, endpoint_of(item.peer), item.at,
          [this, &item](std::span<const uint8_t> envelope, const server::Endpoint& from,
                        const server::Admission* who) {
            host_->on_datagram(envelope, from, item.at, who);
          });
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
  for (;;) {
    now_ += step;
    deliver_due();
    if (now_ >= next_tick) {
      const auto begin = std::chrono::steady_clock::now();
      host_->on_tick(now_);
      host_busy_ += std::chrono::steady_clock::now() - begin;
      ++host_ticks_;
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

game::PlayerInput aggressive_crates_input(uint64_t seed, uint32_t player, Tick tick) {
  // Ten-second phases: four in five send everyone into the same corner,
  // the fifth is a free-for-all with a new direction every 45 ticks.
  const uint64_t phase = mix(seed ^ mix(static_cast<uint64_t>(tick) / 600));
  game::PlayerInput input;
  if (phase % 5 < 4) {
    input.axis_x = (phase & 1) ? game::kAxisMax : -game::kAxisMax;
    input.axis_y = (phase & 2) ? game::kAxisMax : -game::kAxisMax;
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
  return input;
}

}  // namespace rwd::test
