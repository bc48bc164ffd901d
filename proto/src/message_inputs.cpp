// SPDX-License-Identifier: MIT
#include "rewind/proto/message_inputs.h"

#include <cstdint>
#include <string>
#include <string_view>

#include "rewind/proto/input_packing.h"
#include "rewind/proto/input_wire.h"

namespace rwd::proto {
namespace {

Status corrupt(const std::string& what) {
  return Status::Error(ErrorCode::kCorrupt, what);
}

Status repeated_inputs(const google::protobuf::RepeatedPtrField<v1::Input>& inputs,
                       std::vector<rwd::PlayerInput>& out) {
  out.clear();
  for (const v1::Input& wire : inputs) {
    auto in = from_wire(wire);
    if (!in.ok()) return in.status();
    out.push_back(*in);
  }
  return Status::Ok();
}

void put_varint(uint64_t v, std::string& out) {
  while (v >= 0x80) {
    out.push_back(static_cast<char>(v | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<char>(v));
}

bool get_varint(std::string_view in, size_t& at, uint64_t& v) {
  v = 0;
  for (int shift = 0; shift < 64; shift += 7) {
    if (at >= in.size()) return false;
    const auto byte = static_cast<uint8_t>(in[at++]);
    v |= uint64_t{byte & 0x7Fu} << shift;
    if ((byte & 0x80u) == 0) return true;
  }
  return false;
}

constexpr size_t kMaxRelayedRuns = 256;
constexpr uint32_t kMaxSlots = 64;

}  // namespace

void append_relayed_run(uint32_t player, int32_t first_tick, int32_t server_tick,
                        std::span<const rwd::PlayerInput> inputs, std::string& out) {
  out.push_back(static_cast<char>(player));
  const int64_t offset = int64_t{first_tick} - int64_t{server_tick};
  put_varint(static_cast<uint64_t>((offset << 1) ^ (offset >> 63)), out);
  std::string run;
  pack_run(inputs, run);
  // The run's length first, so a reader can find the next run.
  put_varint(run.size(), out);
  out += run;
}

Status relayed_runs(const v1::FinalTicks& finals, std::vector<RelayedRun>& out) {
  out.clear();
  const std::string& bytes = finals.relayed();
  size_t at = 0;
  while (at < bytes.size()) {
    if (out.size() == kMaxRelayedRuns) return corrupt("final_ticks.relayed: more than 256 runs");
    RelayedRun run;
    run.player = static_cast<uint8_t>(bytes[at++]);
    uint64_t zigzag = 0;
    uint64_t length = 0;
    if (run.player >= kMaxSlots || !get_varint(bytes, at, zigzag) ||
        !get_varint(bytes, at, length) || length > bytes.size() - at) {
      out.clear();
      return corrupt("final_ticks.relayed: run " + std::to_string(out.size()) + " is malformed");
    }
    const int64_t offset = static_cast<int64_t>(zigzag >> 1) ^ -static_cast<int64_t>(zigzag & 1);
    const int64_t first = int64_t{finals.server_tick()} + offset;
    if (Status s = unpack_run(std::string_view(bytes).substr(at, length), run.inputs); !s.ok()) {
      out.clear();
      return corrupt("final_ticks.relayed: " + s.message());
    }
    at += length;
    if (first < 0 || first + static_cast<int64_t>(run.inputs.size()) > INT32_MAX) {
      out.clear();
      return corrupt("final_ticks.relayed: a first tick out of range");
    }
    run.first_tick = static_cast<int32_t>(first);
    out.push_back(std::move(run));
  }
  return Status::Ok();
}

Status check_final_tick_inputs(const v1::FinalTicks& finals) {
  std::vector<rwd::PlayerInput> scratch;
  for (int t = 0; t < finals.ticks_size(); ++t) {
    const v1::FinalTick& tick = finals.ticks(t);
    const std::string name = "final_ticks.ticks[" + std::to_string(t) + "]";
    Status status = Status::Ok();
    if (tick.packed_inputs().empty()) {
      if (tick.delta()) return corrupt(name + " is a delta without packed inputs");
      status = repeated_inputs(tick.inputs(), scratch);
    } else if (tick.inputs_size() != 0) {
      return corrupt(name + " has packed and repeated inputs");
    } else if (tick.delta()) {
      status = check_packed_inputs(tick.packed_inputs());
    } else {
      status = unpack_inputs(tick.packed_inputs(), {}, scratch);
    }
    if (!status.ok()) return corrupt(name + ": " + status.message());
  }
  return Status::Ok();
}

Status final_tick_inputs(const v1::FinalTick& tick, std::span<const rwd::PlayerInput> previous,
                         std::vector<rwd::PlayerInput>& out) {
  if (tick.packed_inputs().empty()) {
    if (tick.delta()) return corrupt("a delta final tick without packed inputs");
    return repeated_inputs(tick.inputs(), out);
  }
  if (!tick.delta()) return unpack_inputs(tick.packed_inputs(), {}, out);
  if (previous.empty()) {
    out.clear();
    return corrupt("a delta final tick without the inputs of the tick before it");
  }
  return unpack_inputs(tick.packed_inputs(), previous, out);
}

Status relayed_run_inputs(const v1::RelayedInputs& run, std::vector<rwd::PlayerInput>& out) {
  if (run.packed_inputs().empty()) return repeated_inputs(run.inputs(), out);
  if (run.inputs_size() != 0) {
    out.clear();
    return corrupt("a relayed run with packed and repeated inputs");
  }
  return unpack_run(run.packed_inputs(), out);
}

}  // namespace rwd::proto
