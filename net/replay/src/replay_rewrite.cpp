// SPDX-License-Identifier: MIT
#include "rewind/replay/replay_rewrite.h"
#include "rewind/proto/input_wire.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "rewind/replay/replay_format.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/replay/replay_writer.h"

namespace rwd::replay {
namespace {

// The edit's fields resolved against the game's input spec.
struct ResolvedEdit {
  std::vector<std::pair<InputField, int64_t>> fields;
};

Result<ResolvedEdit> resolve(const InputSpec& spec, const InputEdit& edit) {
  if (edit.fields.empty()) {
    return Status::Error(ErrorCode::kInvalidArgument, "the edit names no input field");
  }
  ResolvedEdit out;
  for (const InputFieldEdit& f : edit.fields) {
    const InputField* found = find_input_field(spec, f.name);
    if (found == nullptr) {
      std::string names;
      for (const InputField& candidate : spec.fields) {
        names += (names.empty() ? "" : ", ") + std::string(candidate.name);
      }
      return Status::Error(
          ErrorCode::kInvalidArgument,
          "the input ('" + std::string(spec.name) + "') has no field '" + f.name + "' (" +
              (names.empty() ? "it has no named fields" : "fields: " + names) + ")");
    }
    if (f.value < found->min || f.value > found->max) {
      return Status::Error(ErrorCode::kInvalidArgument,
                           "input field '" + f.name + "' = " + std::to_string(f.value) +
                               " is outside [" + std::to_string(found->min) + ", " +
                               std::to_string(found->max) + "]");
    }
    out.fields.emplace_back(*found, f.value);
  }
  return out;
}

// Streams every record through a ReplayWriter, so the forgery obeys exactly
// the rules a real recording does.
Result<rwd::PlayerInput> copy_with_edit(ReplayReader& reader, ReplayWriter& writer,
                                        const InputEdit& edit, const ResolvedEdit& resolved) {
  std::optional<rwd::PlayerInput> original;
  std::vector<rwd::PlayerInput> inputs;
  while (true) {
    Result<std::optional<v1::ReplayRecord>> record = reader.next();
    if (!record.ok()) return record.status();
    if (!record->has_value()) break;
    const v1::ReplayRecord& r = **record;
    Status s;
    if (r.has_tick()) {
      const v1::ReplayTick& t = r.tick();
      inputs.clear();
      for (const v1::Input& in : t.inputs()) {
        // The reader already checked every input converts.
        inputs.push_back(*proto::from_wire(in));
      }
      if (t.tick() == edit.tick) {
        rwd::PlayerInput& target = inputs[edit.player];
        original = target;
        for (const auto& [field, value] : resolved.fields) write_input_field(target, field, value);
      }
      s = writer.append_tick(t.tick(), inputs, t.substituted_mask(), t.checksum());
    } else if (r.has_keyframe()) {
      const std::string& state = r.keyframe().state();
      s = writer.append_keyframe(r.keyframe().tick(),
                                 {reinterpret_cast<const uint8_t*>(state.data()), state.size()});
    } else if (r.has_end()) {
      s = writer.finish(r.end().last_final_tick(), r.end().reason());
    }
    if (!s.ok()) return s;
  }
  if (!original) {
    return Status::Error(ErrorCode::kNotFound, "tick " + std::to_string(edit.tick) +
                                                   " is not in the replay (last tick " +
                                                   std::to_string(reader.last_tick()) + ")");
  }
  if (!writer.finished()) {
    if (Status s = writer.flush(); !s.ok()) return s;
  }
  return *original;
}

}  // namespace

Result<InputRewrite> rewrite_replay_input(const std::string& in_path, const std::string& out_path,
                                          const InputEdit& edit, const InputSpec& spec,
                                          bool overwrite) {
  Result<ReplayReader> reader = ReplayReader::open(in_path);
  if (!reader.ok()) return reader.status();
  if (edit.player >= reader->header().player_count()) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "player " + std::to_string(edit.player) + " is not in the replay (" +
                             std::to_string(reader->header().player_count()) + " players)");
  }
  Result<ResolvedEdit> resolved = resolve(spec, edit);
  if (!resolved.ok()) return resolved.status();
  std::error_code ec;
  if (std::filesystem::equivalent(in_path, out_path, ec)) {
    return Status::Error(ErrorCode::kInvalidArgument, "output must differ from the input file");
  }
  ReplayWriterOptions options;
  options.overwrite = overwrite;
  v1::ReplayHeader header = reader->header();
  Result<ReplayWriter> writer = ReplayWriter::open(out_path, header, options);
  if (!writer.ok()) return writer.status();
  Result<rwd::PlayerInput> original = copy_with_edit(*reader, *writer, edit, *resolved);
  if (!original.ok()) {
    // Close before removing so the destructor's flush cannot recreate it.
    { ReplayWriter closing = std::move(*writer); }
    std::filesystem::remove(out_path, ec);
    return original.status();
  }
  InputRewrite rewrite;
  rewrite.before = rewrite.after = *original;
  for (const auto& [field, value] : resolved->fields)
    write_input_field(rewrite.after, field, value);
  rewrite.before_text = describe_input(spec, rewrite.before);
  rewrite.after_text = describe_input(spec, rewrite.after);
  return rewrite;
}

}  // namespace rwd::replay
