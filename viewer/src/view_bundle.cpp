// SPDX-License-Identifier: MIT
#include "rewind/viewer/view_bundle.h"

#include <cstring>
#include <string_view>

#include "byte_io.h"

namespace rwd::viewer {
namespace {

using detail::Reader;
using detail::Writer;

constexpr char kMagic[8] = {'R', 'W', 'D', 'V', 'I', 'E', 'W', '1'};

Status invalid(const std::string& message) {
  return Status::Error(ErrorCode::kInvalidArgument, "view bundle: " + message);
}

Status check(const ViewBundle& b) {
  if (b.game.empty() || b.game.size() > kViewMaxString) return invalid("game name length");
  if (b.setup.player_count < 1 || b.setup.player_count > game::kMaxPlayers) {
    return invalid("player count out of [1, " + std::to_string(game::kMaxPlayers) + "]");
  }
  if (b.identity_note.size() > kViewMaxString) return invalid("identity note too long");
  if (!b.player_names.empty() && b.player_names.size() != b.setup.player_count) {
    return invalid("player names: none or one per player");
  }
  for (const std::string& name : b.player_names) {
    if (name.size() > kViewMaxString) return invalid("a player name is too long");
  }
  if (b.first_tick < 0 || b.first_tick > static_cast<Tick>(kViewMaxTicks)) {
    return invalid("first tick out of [0, " + std::to_string(kViewMaxTicks) + "]");
  }
  if (b.first_tick > 0 && b.start_state.empty()) return invalid("a later first tick needs a state");
  if (b.start_state.size() > kViewMaxStateBytes) return invalid("start state too big");
  if (b.checksums.size() > kViewMaxTicks) return invalid("too many ticks");
  Tick after = b.first_tick;
  for (const ViewKeyframe& k : b.keyframes) {
    if (k.position <= after || k.position > b.end_position()) {
      return invalid("keyframe positions must ascend within the ticks");
    }
    if (k.state.empty() || k.state.size() > kViewMaxStateBytes)
      return invalid("keyframe state size");
    after = k.position;
  }
  if (b.substituted_masks.size() != b.checksums.size() ||
      b.inputs.size() != b.checksums.size() * b.setup.player_count) {
    return invalid("inputs, checksums and masks must cover the same ticks");
  }
  if (b.desync) {
    if (b.desync->tick < 0) return invalid("desync tick is negative");
    if (b.desync->headline.size() > kViewMaxHeadline) return invalid("desync headline too long");
    if (b.desync->client_state.size() > kViewMaxStateBytes) return invalid("client state too big");
  }
  return Status::Ok();
}

}  // namespace

Status encode_view_bundle(const ViewBundle& b, std::vector<uint8_t>& out) {
  if (Status s = check(b); !s.ok()) return s;
  std::vector<uint8_t> bytes;
  bytes.reserve(64 + b.inputs.size() * 8 + b.checksums.size() * 16 +
                (b.desync ? b.desync->client_state.size() : 0));
  Writer w(bytes);
  for (const char c : kMagic) w.put(static_cast<uint8_t>(c), 1);
  w.put(kViewBundleVersion, 4);
  w.str(b.game);
  w.put(b.setup.player_count, 4);
  w.put(b.setup.seed, 8);
  w.put(b.tick_rate_hz, 4);
  w.put(b.identity_matches ? 1 : 0, 1);
  w.str(b.identity_note);
  w.put(b.player_names.size(), 4);
  for (const std::string& name : b.player_names) w.str(name);
  w.put(static_cast<uint32_t>(b.first_tick), 4);
  w.bytes(b.start_state);
  w.put(b.keyframes.size(), 4);
  for (const ViewKeyframe& k : b.keyframes) {
    w.put(static_cast<uint32_t>(k.position), 4);
    w.bytes(k.state);
  }
  w.put(b.checksums.size(), 4);
  detail::put_ticks(w, b.setup.player_count, b.checksums, b.substituted_masks, b.inputs);
  w.put(b.desync ? 1 : 0, 1);
  if (b.desync) {
    w.put(static_cast<uint32_t>(b.desync->tick), 4);
    w.put(b.desync->player, 4);
    w.str(b.desync->headline);
    w.bytes(b.desync->client_state);
  }
  out = std::move(bytes);
  return Status::Ok();
}

Result<ViewBundle> decode_view_bundle(std::span<const uint8_t> bytes) {
  auto corrupt = [](const std::string& message) {
    return Status::Error(ErrorCode::kCorrupt, "view bundle: " + message);
  };
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    return corrupt("not a view bundle (no RWDVIEW1 magic)");
  }
  Reader r(bytes, sizeof kMagic);
  const uint64_t version = r.get(4, "version");
  if (r.ok() && (version < 1 || version > kViewBundleVersion)) {
    return corrupt("version " + std::to_string(version) + " (this build reads 1 to " +
                   std::to_string(kViewBundleVersion) + ")");
  }
  ViewBundle b;
  b.game = r.str(kViewMaxString, "game name");
  const uint64_t players = r.get(4, "player count");
  if (r.ok() && (players < 1 || players > game::kMaxPlayers))
    r.fail("player count", "is out of range");
  b.setup.player_count = static_cast<uint32_t>(players);
  b.setup.seed = r.get(8, "seed");
  b.tick_rate_hz = static_cast<uint32_t>(r.get(4, "tick rate"));
  const uint64_t identity = r.get(1, "identity flag");
  if (r.ok() && identity > 1) r.fail("identity flag", "is neither 0 nor 1");
  b.identity_matches = identity == 1;
  b.identity_note = r.str(kViewMaxString, "identity note");
  const uint64_t names = r.get(4, "name count");
  if (r.ok() && names != 0 && names != players)
    r.fail("name count", "is neither 0 nor the players");
  for (uint64_t i = 0; r.ok() && i < names; ++i) {
    b.player_names.push_back(r.str(kViewMaxString, "player name"));
  }
  if (version >= 2) {
    b.first_tick = static_cast<Tick>(static_cast<uint32_t>(r.get(4, "first tick")));
    if (r.ok() && (b.first_tick < 0 || b.first_tick > static_cast<Tick>(kViewMaxTicks))) {
      r.fail("first tick", "is out of range");
    }
    const auto state = r.run(kViewMaxStateBytes, "start state");
    b.start_state.assign(state.begin(), state.end());
    if (r.ok() && b.first_tick > 0 && b.start_state.empty()) {
      r.fail("start state", "is empty after a later first tick");
    }
    const uint64_t keyframes = r.get(4, "keyframe count");
    // Each takes at least 8 bytes and a state byte.
    if (r.ok() && keyframes > r.remaining() / 9) r.fail("keyframe count", "runs past the end");
    Tick after = b.first_tick;
    for (uint64_t k = 0; r.ok() && k < keyframes; ++k) {
      ViewKeyframe keyframe;
      keyframe.position = static_cast<Tick>(static_cast<uint32_t>(r.get(4, "keyframe position")));
      if (r.ok() && keyframe.position <= after) r.fail("keyframe position", "does not ascend");
      const auto keyframe_state = r.run(kViewMaxStateBytes, "keyframe state");
      if (r.ok() && keyframe_state.empty()) r.fail("keyframe state", "is empty");
      keyframe.state.assign(keyframe_state.begin(), keyframe_state.end());
      after = keyframe.position;
      b.keyframes.push_back(std::move(keyframe));
    }
  }
  detail::get_ticks(r, version >= 3 ? detail::InputEncoding::kBytes : detail::InputEncoding::kStick,
                    players, kViewMaxTicks, b.checksums, b.substituted_masks, b.inputs);
  const uint64_t has_desync = r.get(1, "desync flag");
  if (r.ok() && has_desync > 1) r.fail("desync flag", "is neither 0 nor 1");
  if (r.ok() && !b.keyframes.empty() && b.keyframes.back().position > b.end_position()) {
    r.fail("keyframe position", "is past the ticks");
  }
  if (r.ok() && has_desync == 1) {
    ViewDesync d;
    d.tick = static_cast<Tick>(static_cast<uint32_t>(r.get(4, "desync tick")));
    if (r.ok() && d.tick < 0) r.fail("desync tick", "is negative");
    d.player = static_cast<uint32_t>(r.get(4, "desync player"));
    d.headline = r.str(kViewMaxHeadline, "desync headline");
    const auto state = r.run(kViewMaxStateBytes, "client state");
    d.client_state.assign(state.begin(), state.end());
    b.desync = std::move(d);
  }
  if (r.ok() && r.remaining() != 0) {
    r.fail("end", ("has " + std::to_string(r.remaining()) + " bytes left over").c_str());
  }
  if (!r.ok()) return corrupt(r.error());
  return b;
}

}  // namespace rwd::viewer
