// SPDX-License-Identifier: MIT
#include "rewind/proto/message_inputs.h"

#include <string>

#include "rewind/proto/input_packing.h"
#include "rewind/proto/input_wire.h"

namespace rwd::proto {
namespace {

Status corrupt(const std::string& what) {
  return Status::Error(ErrorCode::kCorrupt, what);
}

Status repeated_inputs(const google::protobuf::RepeatedPtrField<v1::Input>& inputs,
                       std::vector<game::PlayerInput>& out) {
  out.clear();
  for (const v1::Input& wire : inputs) {
    auto in = from_wire(wire);
    if (!in.ok()) return in.status();
    if (in->axis_x < -game::kAxisMax || in->axis_x > game::kAxisMax ||
        in->axis_y < -game::kAxisMax || in->axis_y > game::kAxisMax) {
      return corrupt("an input axis outside [-1000, 1000]");
    }
    out.push_back(*in);
  }
  return Status::Ok();
}

}  // namespace

Status final_tick_inputs(const v1::FinalTicks& finals,
                         std::vector<std::vector<game::PlayerInput>>& out) {
  out.resize(static_cast<size_t>(finals.ticks_size()));
  for (int t = 0; t < finals.ticks_size(); ++t) {
    const v1::FinalTick& tick = finals.ticks(t);
    std::vector<game::PlayerInput>& inputs = out[static_cast<size_t>(t)];
    const std::string name = "final_ticks.ticks[" + std::to_string(t) + "]";
    Status status = Status::Ok();
    if (tick.packed_inputs().empty()) {
      if (tick.delta()) return corrupt(name + " is a delta without packed inputs");
      status = repeated_inputs(tick.inputs(), inputs);
    } else if (tick.inputs_size() != 0) {
      return corrupt(name + " has packed and repeated inputs");
    } else if (tick.delta()) {
      if (t == 0 || finals.ticks(t - 1).tick() != tick.tick() - 1) {
        return corrupt(name + " is a delta but does not follow the tick before it");
      }
      status = unpack_inputs(tick.packed_inputs(), out[static_cast<size_t>(t) - 1], inputs);
    } else {
      status = unpack_inputs(tick.packed_inputs(), {}, inputs);
    }
    if (!status.ok()) return corrupt(name + ": " + status.message());
  }
  return Status::Ok();
}

Status relayed_run_inputs(const v1::RelayedInputs& run, std::vector<game::PlayerInput>& out) {
  if (run.packed_inputs().empty()) return repeated_inputs(run.inputs(), out);
  if (run.inputs_size() != 0) {
    out.clear();
    return corrupt("a relayed run with packed and repeated inputs");
  }
  return unpack_run(run.packed_inputs(), out);
}

}  // namespace rwd::proto
