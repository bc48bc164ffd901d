// SPDX-License-Identifier: MIT
#include "fake_server.h"

#include <stdexcept>

#include "rewind/net/address_cookie.h"
#include "rewind/net/chunked_transfer.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/proto/input_wire.h"
#include "rewind/proto/message_inputs.h"

namespace rwd::test {

FakeServer::FakeServer(const FakeMatch& match)
    : match_(match), connection_(net::TimePoint{}, match.connection_id) {
  auto sim = game::Simulation::create(match.game, {match.players, match.seed});
  if (!sim.ok()) throw std::runtime_error("fake server: " + sim.status().message());
  sim_ = std::move(*sim);
}

std::optional<v1::Envelope> FakeServer::read(std::span<const uint8_t> datagram,
                                             net::TimePoint now) {
  std::vector<uint8_t> opened;
  if (secure_) {
    if (!secure_->open(datagram, opened).ok()) return std::nullopt;
    datagram = opened;
  } else if (net::cookie_packet_kind(datagram) == net::CookiePacket::kJoin &&
             datagram.size() > net::kJoinOverhead) {
    datagram = datagram.subspan(net::kJoinOverhead);  // a tokenless join: past its cookie
  }
  auto envelope = net::decode_envelope(datagram);
  if (!envelope.ok()) return std::nullopt;
  if (envelope->connection_id() == match_.connection_id)
    (void)connection_.on_receive(*envelope, now);
  return std::move(*envelope);
}

std::vector<uint8_t> FakeServer::encode(v1::Envelope& envelope, net::TimePoint now) {
  connection_.stamp(envelope, now);
  std::vector<uint8_t> bytes;
  if (!net::encode_envelope(envelope, bytes).ok()) {
    throw std::runtime_error("fake server: the codec refused an envelope");
  }
  if (!secure_) return bytes;
  std::vector<uint8_t> sealed;
  secure_->seal(bytes, sealed);
  return sealed;
}

std::vector<uint8_t> FakeServer::join_accept(uint64_t nonce, uint32_t player, net::TimePoint now) {
  v1::Envelope envelope;
  v1::JoinAccept* accept = envelope.mutable_join_accept();
  accept->set_nonce(nonce);
  accept->set_connection_id(match_.connection_id);
  accept->set_player(player);
  accept->set_player_count(match_.players);
  accept->set_game(match_.game);
  accept->set_seed(match_.seed);
  accept->set_tick_rate_hz(match_.tick_rate_hz);
  accept->set_window_ticks(match_.window_ticks);
  accept->set_spectator(player >= match_.players);
  return encode(envelope, now);
}

std::vector<uint8_t> FakeServer::join_reject(uint64_t nonce, const std::string& reason) {
  // Sent before any connection exists: unstamped, like the server's.
  v1::Envelope envelope;
  envelope.set_protocol_version(net::kProtocolVersion);
  envelope.mutable_join_reject()->set_nonce(nonce);
  envelope.mutable_join_reject()->set_reason(reason);
  std::vector<uint8_t> bytes;
  if (!net::encode_envelope(envelope, bytes).ok()) {
    throw std::runtime_error("fake server: the codec refused a JoinReject");
  }
  return bytes;
}

std::vector<uint8_t> FakeServer::match_start(Tick server_tick, net::TimePoint now) {
  v1::Envelope envelope;
  envelope.mutable_match_start()->set_start_tick(0);
  envelope.mutable_match_start()->set_server_tick(server_tick);
  return encode(envelope, now);
}

std::vector<uint8_t> FakeServer::match_end(Tick last_final_tick, net::TimePoint now) {
  v1::Envelope envelope;
  envelope.mutable_match_end()->set_last_final_tick(last_final_tick);
  envelope.mutable_match_end()->set_reason("max ticks");
  return encode(envelope, now);
}

std::vector<uint8_t> FakeServer::disconnect(const std::string& reason, net::TimePoint now) {
  v1::Envelope envelope;
  envelope.mutable_disconnect()->set_reason(reason);
  return encode(envelope, now);
}

void FakeServer::step(const std::vector<rwd::PlayerInput>& inputs) {
  TickRecord record;
  record.inputs = inputs;
  sim_->serialize(record.state_before);
  record.checksum_before = sim_->checksum();
  if (rwd::Status status = sim_->step(inputs); !status.ok()) {
    throw std::runtime_error("FakeServer: " + status.message());
  }
  record.checksum = sim_->checksum();
  ticks_[next_tick_++] = std::move(record);
}

std::vector<uint8_t> FakeServer::final_ticks(
    Tick first, Tick last, Tick input_ack, net::TimePoint now,
    std::optional<std::pair<Tick, uint64_t>> checksum_override,
    const std::vector<Relayed>& relayed) {
  v1::Envelope envelope;
  v1::FinalTicks* finals = envelope.mutable_final_ticks();
  finals->set_input_ack_tick(input_ack);
  finals->set_server_tick(next_tick_);
  for (Tick t = first; t <= last; ++t) {
    const TickRecord& record = ticks_.at(t);
    v1::FinalTick* tick = finals->add_ticks();
    tick->set_tick(t);
    for (const rwd::PlayerInput& input : record.inputs) *tick->add_inputs() = proto::to_wire(input);
    tick->set_checksum(checksum_override && checksum_override->first == t
                           ? checksum_override->second
                           : record.checksum);
  }
  for (const Relayed& run : relayed) {
    proto::append_relayed_run(run.player, run.first_tick, next_tick_, run.inputs,
                              *finals->mutable_relayed());
  }
  return encode(envelope, now);
}

std::vector<std::vector<uint8_t>> FakeServer::resync_chunks(uint32_t snapshot_id, Tick tick,
                                                            net::TimePoint now) {
  const std::vector<uint8_t>& state = state_at(tick);
  const Result<uint32_t> count = net::plan_chunks(state.size(), net::kResyncChunkLimits);
  if (!count.ok()) throw std::runtime_error("fake server: " + count.status().message());
  std::vector<std::vector<uint8_t>> out;
  for (uint32_t i = 0; i < *count; ++i) {
    const std::span<const uint8_t> part = net::chunk_at(state, i, net::kResyncChunkLimits);
    v1::Envelope envelope;
    v1::ResyncChunk* chunk = envelope.mutable_resync_chunk();
    chunk->set_snapshot_id(snapshot_id);
    chunk->set_tick(tick);
    chunk->set_checksum(checksum_at(tick));
    chunk->set_chunk_index(i);
    chunk->set_chunk_count(*count);
    chunk->set_total_size(static_cast<uint32_t>(state.size()));
    chunk->set_chunk(part.data(), part.size());
    out.push_back(encode(envelope, now));
  }
  return out;
}

}  // namespace rwd::test
