// SPDX-License-Identifier: MIT
#include "rewind/net/envelope_codec.h"

#include "rewind/proto/message_inputs.h"

#include <limits>
#include <string>
#include <string_view>

#include <google/protobuf/stubs/logging.h>

namespace rwd::net {
namespace {

using v1::Envelope;

Status corrupt(std::string message) {
  return Status::Error(ErrorCode::kCorrupt, "envelope: " + std::move(message));
}

Status check_string(std::string_view field, const std::string& value, size_t max_bytes) {
  if (value.size() > max_bytes) {
    return corrupt(std::string(field) + " is " + std::to_string(value.size()) + " bytes, limit " +
                   std::to_string(max_bytes));
  }
  return Status::Ok();
}

// Since protocol 3 an input is its bytes; the stick fields are for old
// replay files only. What the bytes may hold is the game's to check.
bool input_well_formed(const v1::Input& input) {
  return input.data().size() <= rwd::kInputCapacity &&
         (input.data().empty() || input.data().back() != '\0') && input.axis_x() == 0 &&
         input.axis_y() == 0 && input.buttons() == 0;
}

// Every datagram in and out is validated, inputs by the dozen: field names
// are only put together once something is wrong.
Status input_error(const std::string& field, int index, const v1::Input& input) {
  const std::string name = field + "[" + std::to_string(index) + "]";
  if (input.data().size() > rwd::kInputCapacity) {
    return corrupt(name + " has " + std::to_string(input.data().size()) + " bytes, limit " +
                   std::to_string(rwd::kInputCapacity));
  }
  if (!input.data().empty() && input.data().back() == '\0') {
    return corrupt(name + " ends in a zero byte (trailing zeros are left out)");
  }
  return corrupt(name + " sets the stick fields of replay formats 1 and 2");
}

// A run of inputs starting at first_tick: the last tick must still be an
// int32, so higher layers can compute first_tick + i without overflow.
template <class Inputs>
Status check_input_run(std::string_view field, uint32_t player, int32_t first_tick,
                       const Inputs& inputs) {
  if (player >= kMaxPlayerSlots) {
    return corrupt(std::string(field) + ".player " + std::to_string(player) +
                   " >= " + std::to_string(kMaxPlayerSlots));
  }
  if (static_cast<size_t>(inputs.size()) > kMaxInputsPerFrame) {
    return corrupt(std::string(field) + " has " + std::to_string(inputs.size()) +
                   " inputs, limit " + std::to_string(kMaxInputsPerFrame));
  }
  if (first_tick < 0 ||
      first_tick > std::numeric_limits<int32_t>::max() - static_cast<int32_t>(inputs.size())) {
    return corrupt(std::string(field) + ".first_tick " + std::to_string(first_tick) +
                   " out of range");
  }
  for (int i = 0; i < inputs.size(); ++i) {
    if (!input_well_formed(inputs.Get(i))) {
      return input_error(std::string(field) + ".inputs", i, inputs.Get(i));
    }
  }
  return Status::Ok();
}

// A relayed run: its header and repeated inputs as any run, and its packed
// inputs (if any) readable, in range, alone, and ending within int32 ticks.
Status check_relayed(std::string_view field, const v1::RelayedInputs& run) {
  if (Status s = check_input_run(field, run.player(), run.first_tick(), run.inputs()); !s.ok()) {
    return s;
  }
  if (run.packed_inputs().empty()) return Status::Ok();
  std::vector<rwd::PlayerInput> inputs;
  if (Status s = proto::relayed_run_inputs(run, inputs); !s.ok()) {
    return corrupt(std::string(field) + ": " + s.message());
  }
  if (run.first_tick() >
      std::numeric_limits<int32_t>::max() - static_cast<int32_t>(inputs.size())) {
    return corrupt(std::string(field) + ".first_tick " + std::to_string(run.first_tick()) +
                   " out of range");
  }
  return Status::Ok();
}

Status check_chunk(std::string_view field, uint32_t chunk_index, uint32_t chunk_count,
                   uint32_t max_chunks, uint32_t total_size, uint32_t max_total,
                   const std::string& chunk) {
  const std::string f(field);
  if (chunk_count == 0 || chunk_count > max_chunks) {
    return corrupt(f + ".chunk_count " + std::to_string(chunk_count) + " not in [1, " +
                   std::to_string(max_chunks) + "]");
  }
  if (chunk_index >= chunk_count) {
    return corrupt(f + ".chunk_index " + std::to_string(chunk_index) + " >= chunk_count " +
                   std::to_string(chunk_count));
  }
  if (chunk.size() > kMaxChunkBytes) {
    return corrupt(f + ".chunk is " + std::to_string(chunk.size()) + " bytes, limit " +
                   std::to_string(kMaxChunkBytes));
  }
  // A total that chunk_count full chunks cannot carry would make the
  // reassembler wait forever; reject it here rather than there.
  if (total_size > max_total ||
      static_cast<uint64_t>(total_size) > static_cast<uint64_t>(chunk_count) * kMaxChunkBytes) {
    return corrupt(f + ".total_size " + std::to_string(total_size) + " out of range for " +
                   std::to_string(chunk_count) + " chunks");
  }
  if (chunk.size() > total_size) {
    return corrupt(f + ".chunk larger than total_size");
  }
  return Status::Ok();
}

Status check_tick(std::string_view field, int32_t tick, int32_t min_tick) {
  if (tick < min_tick) {
    return corrupt(std::string(field) + " " + std::to_string(tick) + " < " +
                   std::to_string(min_tick));
  }
  return Status::Ok();
}

Status check_payload(const Envelope& e) {
  switch (e.payload_case()) {
    case Envelope::kJoinRequest: {
      const auto& m = e.join_request();
      if (Status s = check_string("join_request.game", m.game(), kMaxStringBytes); !s.ok())
        return s;
      return check_string("join_request.client_name", m.client_name(), kMaxClientNameBytes);
    }
    case Envelope::kJoinAccept: {
      const auto& m = e.join_accept();
      if (m.connection_id() == 0) return corrupt("join_accept.connection_id is 0");
      if (m.player_count() == 0 || m.player_count() > kMaxPlayerSlots) {
        return corrupt("join_accept.player_count " + std::to_string(m.player_count()) +
                       " not in [1, " + std::to_string(kMaxPlayerSlots) + "]");
      }
      // A spectator's seat id follows the player slots.
      if (m.spectator() ? m.player() < m.player_count() || m.player() >= kMaxPlayerSlots
                        : m.player() >= m.player_count()) {
        return corrupt(
            "join_accept.player " + std::to_string(m.player()) +
            (m.spectator() ? " is not a spectator seat after player_count " : " >= player_count ") +
            std::to_string(m.player_count()));
      }
      if (m.tick_rate_hz() == 0 || m.tick_rate_hz() > kMaxTickRateHz) {
        return corrupt("join_accept.tick_rate_hz " + std::to_string(m.tick_rate_hz()) +
                       " not in [1, " + std::to_string(kMaxTickRateHz) + "]");
      }
      return check_string("join_accept.game", m.game(), kMaxStringBytes);
    }
    case Envelope::kJoinReject:
      return check_string("join_reject.reason", e.join_reject().reason(), kMaxStringBytes);
    case Envelope::kMatchStart:
      return check_tick("match_start.start_tick", e.match_start().start_tick(), 0);
    case Envelope::kMatchEnd:
      if (Status s = check_tick("match_end.last_final_tick", e.match_end().last_final_tick(), -1);
          !s.ok()) {
        return s;
      }
      return check_string("match_end.reason", e.match_end().reason(), kMaxStringBytes);
    case Envelope::kDisconnect:
      return check_string("disconnect.reason", e.disconnect().reason(), kMaxStringBytes);
    case Envelope::kPing:
    case Envelope::kPong:
      return Status::Ok();
    case Envelope::kInputFrame: {
      const auto& m = e.input_frame();
      if (Status s = check_tick("input_frame.last_final_tick_seen", m.last_final_tick_seen(), -1);
          !s.ok()) {
        return s;
      }
      return check_input_run("input_frame", m.player(), m.first_tick(), m.inputs());
    }
    case Envelope::kRelayedInputs:
      return check_relayed("relayed_inputs", e.relayed_inputs());
    case Envelope::kFinalTicks: {
      const auto& m = e.final_ticks();
      if (static_cast<size_t>(m.ticks_size()) > kMaxFinalTicksPerPacket) {
        return corrupt("final_ticks has " + std::to_string(m.ticks_size()) + " ticks, limit " +
                       std::to_string(kMaxFinalTicksPerPacket));
      }
      for (int t = 0; t < m.ticks_size(); ++t) {
        const v1::FinalTick& ft = m.ticks(t);
        auto field = [t] { return "final_ticks.ticks[" + std::to_string(t) + "]"; };
        if (ft.tick() < 0) return check_tick(field() + ".tick", ft.tick(), 0);
        if (static_cast<uint32_t>(ft.inputs_size()) > kMaxPlayerSlots) {
          return corrupt(field() + " has " + std::to_string(ft.inputs_size()) + " inputs, limit " +
                         std::to_string(kMaxPlayerSlots));
        }
        for (int i = 0; i < ft.inputs_size(); ++i) {
          if (!input_well_formed(ft.inputs(i)))
            return input_error(field() + ".inputs", i, ft.inputs(i));
        }
      }
      std::vector<proto::RelayedRun> runs;
      if (Status s = proto::relayed_runs(m, runs); !s.ok()) return s;
      if (Status s = proto::check_final_tick_inputs(m); !s.ok()) return s;
      return check_tick("final_ticks.input_ack_tick", m.input_ack_tick(), -1);
    }
    case Envelope::kDesyncReport: {
      const auto& m = e.desync_report();
      if (Status s = check_tick("desync_report.tick", m.tick(), 0); !s.ok()) return s;
      return check_chunk("desync_report", m.chunk_index(), m.chunk_count(), kMaxDesyncChunks,
                         m.total_size(), kMaxDesyncDumpBytes, m.chunk());
    }
    case Envelope::kResyncChunk: {
      const auto& m = e.resync_chunk();
      if (Status s = check_tick("resync_chunk.tick", m.tick(), 0); !s.ok()) return s;
      return check_chunk("resync_chunk", m.chunk_index(), m.chunk_count(), kMaxResyncChunks,
                         m.total_size(), kMaxResyncStateBytes, m.chunk());
    }
    case Envelope::kResyncRequest: {
      const auto& m = e.resync_request();
      if (Status s = check_tick("resync_request.desync_tick", m.desync_tick(), 0); !s.ok())
        return s;
      return check_string("resync_request.refused_reason", m.refused_reason(), kMaxStringBytes);
    }
    case Envelope::PAYLOAD_NOT_SET:
      return corrupt("no payload");
  }
  // A payload number this build does not know (parsed as an unknown field,
  // so payload_case() cannot name it) ends up as PAYLOAD_NOT_SET above; this
  // line only satisfies -Wreturn-type.
  return corrupt("unknown payload");
}

Status validate_header(const Envelope& envelope) {
  if (envelope.protocol_version() != kProtocolVersion) {
    return corrupt("protocol_version " + std::to_string(envelope.protocol_version()) +
                   ", expected " + std::to_string(kProtocolVersion));
  }
  if (envelope.payload_case() == Envelope::PAYLOAD_NOT_SET) return corrupt("no payload");
  // Every message after the handshake names its connection; the server
  // answers a JoinRequest it cannot accept before any id exists.
  const bool pre_connection = envelope.payload_case() == Envelope::kJoinRequest ||
                              envelope.payload_case() == Envelope::kJoinReject;
  if (envelope.connection_id() == 0 && !pre_connection) {
    return corrupt("connection_id is 0 on a post-handshake message");
  }
  return Status::Ok();
}

}  // namespace

Status validate_envelope(const Envelope& envelope) {
  if (Status s = validate_header(envelope); !s.ok()) return s;
  return check_payload(envelope);
}

Status decode_envelope(std::span<const uint8_t> bytes, Envelope& out) {
  if (bytes.empty()) return corrupt("empty datagram");
  if (bytes.size() > kMaxDatagramBytes) {
    return corrupt("datagram is " + std::to_string(bytes.size()) + " bytes, limit " +
                   std::to_string(kMaxDatagramBytes));
  }
  bool parsed = false;
  {
    // protobuf logs an ERROR line for every string field with invalid UTF-8;
    // a peer could flood the server log with one datagram per line. The
    // rejection below is the report. LogSilencer is thread-safe (a counter)
    // and only hides non-fatal messages while a parse runs.
    google::protobuf::LogSilencer quiet;
    // The size check above keeps the int cast exact.
    parsed = out.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()));
  }
  if (!parsed) return corrupt("not a valid protobuf Envelope");
  return validate_envelope(out);
}

Result<Envelope> decode_envelope(std::span<const uint8_t> bytes) {
  Envelope envelope;
  if (Status s = decode_envelope(bytes, envelope); !s.ok()) return s;
  return envelope;
}

Status encode_envelope(const Envelope& envelope, std::vector<uint8_t>& out, EncodeCheck check) {
  out.clear();
  if (Status s =
          check == EncodeCheck::kFull ? validate_envelope(envelope) : validate_header(envelope);
      !s.ok()) {
    return Status::Error(ErrorCode::kInvalidArgument, "encode refused: " + s.message());
  }
  const size_t size = envelope.ByteSizeLong();
  if (size > kMaxDatagramBytes) {
    return Status::Error(ErrorCode::kCapacity, "envelope: encoded size " + std::to_string(size) +
                                                   " bytes exceeds " +
                                                   std::to_string(kMaxDatagramBytes));
  }
  out.resize(size);
  if (size > 0 && !envelope.SerializeToArray(out.data(), static_cast<int>(size))) {
    out.clear();
    return Status::Error(ErrorCode::kInvalidArgument, "envelope: serialization failed");
  }
  return Status::Ok();
}

}  // namespace rwd::net
