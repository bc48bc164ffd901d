// SPDX-License-Identifier: MIT
#include "rewind/replay/replay_view.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <regex>
#include <string_view>

#include "rewind/proto/input_wire.h"
#include "rewind/replay/engine_identity.h"

namespace rwd::replay {

Result<viewer::ViewBundle> view_bundle_from_replay(ReplayReader& reader, ReplayViewInfo* info) {
  const v1::ReplayHeader& header = reader.header();
  viewer::ViewBundle b;
  b.game = header.game();
  b.setup.player_count = header.player_count();
  b.setup.seed = header.seed();
  b.tick_rate_hz = header.tick_rate_hz();
  const VersionCheck versions = check_versions(header);
  b.identity_matches = versions.matches();
  if (!versions.matches()) {
    b.identity_note = "recorded by " + versions.recorded_label() + ": " + versions.differences[0];
    if (b.identity_note.size() > viewer::kViewMaxString)
      b.identity_note.resize(viewer::kViewMaxString);
  }
  const uint32_t players = b.setup.player_count;
  if (b.game.empty() || b.game.size() > viewer::kViewMaxString || players < 1 ||
      players > game::kMaxPlayers) {
    return Status::Error(ErrorCode::kInvalidArgument, "replay header: game \"" + b.game +
                                                          "\" with " + std::to_string(players) +
                                                          " players cannot be viewed");
  }
  ReplayViewInfo local;
  ReplayViewInfo& out = info != nullptr ? *info : local;
  for (;;) {
    Result<std::optional<v1::ReplayRecord>> next = reader.next();
    if (!next.ok()) {
      out.problem = next.status().message();
      break;
    }
    if (!next->has_value()) break;
    const v1::ReplayRecord& record = **next;
    if (record.has_keyframe()) {
      // The state after its tick: the viewer seeks through it. One the
      // bundle cannot hold (out of order, too big) is left out.
      const Tick position = record.keyframe().tick() + 1;
      const std::string& state = record.keyframe().state();
      const Tick after = b.keyframes.empty() ? 0 : b.keyframes.back().position;
      if (position > after && position <= static_cast<Tick>(b.checksums.size()) && !state.empty() &&
          state.size() <= viewer::kViewMaxStateBytes) {
        b.keyframes.push_back({position, std::vector<uint8_t>(state.begin(), state.end())});
      }
      continue;
    }
    if (!record.has_tick()) continue;
    const v1::ReplayTick& tick = record.tick();
    if (static_cast<uint32_t>(tick.inputs_size()) != players ||
        b.checksums.size() >= viewer::kViewMaxTicks) {
      out.problem = "tick " + std::to_string(tick.tick()) + " cannot be viewed (" +
                    std::to_string(tick.inputs_size()) + " inputs for " + std::to_string(players) +
                    " players)";
      break;
    }
    std::vector<rwd::PlayerInput> inputs;
    for (const v1::Input& wire : tick.inputs()) {
      Result<rwd::PlayerInput> input = proto::from_wire(wire);
      if (!input.ok()) break;
      inputs.push_back(*input);
    }
    if (inputs.size() != players) {
      out.problem = "tick " + std::to_string(tick.tick()) + " holds an input out of range";
      break;
    }
    b.inputs.insert(b.inputs.end(), inputs.begin(), inputs.end());
    b.checksums.push_back(tick.checksum());
    b.substituted_masks.push_back(tick.substituted_mask());
  }
  out.file_state = reader.state();
  return b;
}

Result<viewer::ViewBundle> load_view_bundle(const std::string& path, ReplayViewInfo* info) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::Error(ErrorCode::kIo, "cannot read '" + path + "'");
  char magic[8] = {};
  in.read(magic, sizeof magic);
  if (in.gcount() == sizeof magic && std::string_view(magic, sizeof magic) == "RWDVIEW1") {
    in.seekg(0);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                     std::istreambuf_iterator<char>());
    if (info != nullptr) info->file_state = ReadState::kComplete;
    return viewer::decode_view_bundle(bytes);
  }
  Result<ReplayReader> reader = ReplayReader::open(path);
  if (!reader.ok()) return reader.status();
  return view_bundle_from_replay(*reader, info);
}

Status attach_desync_report(viewer::ViewBundle& bundle, const std::string& bin_path) {
  static const std::regex kName(R"((^|.*/)desync_p(\d{1,9})_t(\d{1,9})_r(\d{1,9})\.bin$)");
  std::smatch m;
  if (!std::regex_match(bin_path, m, kName)) {
    return Status::Error(
        ErrorCode::kInvalidArgument,
        "desync report: '" + bin_path + "' is not a server's desync_pP_tT_rR.bin file");
  }
  viewer::ViewDesync d;
  d.player = static_cast<uint32_t>(std::stoul(m[2].str()));
  d.tick = static_cast<Tick>(std::stol(m[3].str()));
  if (d.tick + 1 > static_cast<Tick>(bundle.tick_count())) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "desync report: tick " + std::to_string(d.tick) +
                             " is past the replay's " + std::to_string(bundle.tick_count()) +
                             " ticks");
  }
  std::ifstream bin(bin_path, std::ios::binary);
  if (!bin) return Status::Error(ErrorCode::kIo, "desync report: cannot read '" + bin_path + "'");
  d.client_state.assign(std::istreambuf_iterator<char>(bin), std::istreambuf_iterator<char>());
  if (d.client_state.size() > viewer::kViewMaxStateBytes) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "desync report: '" + bin_path + "' is larger than a state can be");
  }
  std::ifstream txt(bin_path.substr(0, bin_path.size() - 4) + ".txt");
  if (txt) std::getline(txt, d.headline);
  if (d.headline.size() > viewer::kViewMaxHeadline) d.headline.resize(viewer::kViewMaxHeadline);
  bundle.desync = std::move(d);
  return Status::Ok();
}

}  // namespace rwd::replay
