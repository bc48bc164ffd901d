// SPDX-License-Identifier: MIT
#include "rewind/viewer/live_ticks.h"

#include <cstring>

#include "byte_io.h"
#include "rewind/game/game.h"
#include "rewind/viewer/view_bundle.h"

namespace rwd::viewer {
namespace {

constexpr char kMagic[8] = {'R', 'W', 'D', 'L', 'I', 'V', 'E', '1'};

Status invalid(const std::string& message) {
  return Status::Error(ErrorCode::kInvalidArgument, "live ticks: " + message);
}

Status check(const LiveTicks& b) {
  if (b.player_count < 1 || b.player_count > game::kMaxPlayers) {
    return invalid("player count out of [1, " + std::to_string(game::kMaxPlayers) + "]");
  }
  if (!b.player_names.empty() && b.player_names.size() != b.player_count) {
    return invalid("player names: none or one per player");
  }
  for (const std::string& name : b.player_names) {
    if (name.size() > kViewMaxString) return invalid("a player name is too long");
  }
  if (b.newest_final < kNoTick) return invalid("newest final tick below -1");
  if (b.first_tick < 0) return invalid("first tick is negative");
  if (b.checksums.size() > kLiveMaxBatchTicks) return invalid("too many ticks for one batch");
  if (b.substituted_masks.size() != b.checksums.size() ||
      b.inputs.size() != b.checksums.size() * b.player_count) {
    return invalid("inputs, checksums and masks must cover the same ticks");
  }
  return Status::Ok();
}

}  // namespace

Status encode_live_ticks(const LiveTicks& b, std::vector<uint8_t>& out) {
  if (Status s = check(b); !s.ok()) return s;
  std::vector<uint8_t> bytes;
  bytes.reserve(48 + b.checksums.size() * (16 + 8 * size_t{b.player_count}));
  detail::Writer w(bytes);
  for (const char c : kMagic) w.put(static_cast<uint8_t>(c), 1);
  w.put(kLiveTicksVersion, 4);
  w.put(b.player_count, 4);
  w.put(b.player_names.size(), 4);
  for (const std::string& name : b.player_names) w.str(name);
  w.put(static_cast<uint32_t>(b.newest_final), 4);
  w.put(b.ended ? 1 : 0, 1);
  w.put(static_cast<uint32_t>(b.first_tick), 4);
  w.put(b.checksums.size(), 4);
  detail::put_ticks(w, b.player_count, b.checksums, b.substituted_masks, b.inputs);
  out = std::move(bytes);
  return Status::Ok();
}

Result<LiveTicks> decode_live_ticks(std::span<const uint8_t> bytes) {
  auto corrupt = [](const std::string& message) {
    return Status::Error(ErrorCode::kCorrupt, "live ticks: " + message);
  };
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    return corrupt("not a live tick batch (no RWDLIVE1 magic)");
  }
  detail::Reader r(bytes, sizeof kMagic);
  const uint64_t version = r.get(4, "version");
  if (r.ok() && version != kLiveTicksVersion) {
    return corrupt("version " + std::to_string(version) + " (this build reads " +
                   std::to_string(kLiveTicksVersion) + ")");
  }
  LiveTicks b;
  const uint64_t players = r.get(4, "player count");
  if (r.ok() && (players < 1 || players > game::kMaxPlayers)) {
    r.fail("player count", "is out of range");
  }
  b.player_count = static_cast<uint32_t>(players);
  const uint64_t names = r.get(4, "name count");
  if (r.ok() && names != 0 && names != players) {
    r.fail("name count", "is neither 0 nor the players");
  }
  for (uint64_t i = 0; r.ok() && i < names; ++i) {
    b.player_names.push_back(r.str(kViewMaxString, "player name"));
  }
  b.newest_final = static_cast<Tick>(static_cast<uint32_t>(r.get(4, "newest final tick")));
  if (r.ok() && b.newest_final < kNoTick) r.fail("newest final tick", "is below -1");
  const uint64_t ended = r.get(1, "ended flag");
  if (r.ok() && ended > 1) r.fail("ended flag", "is neither 0 nor 1");
  b.ended = ended == 1;
  b.first_tick = static_cast<Tick>(static_cast<uint32_t>(r.get(4, "first tick")));
  if (r.ok() && b.first_tick < 0) r.fail("first tick", "is negative");
  detail::get_ticks(r, detail::InputEncoding::kBytes, players, kLiveMaxBatchTicks, b.checksums,
                    b.substituted_masks, b.inputs);
  if (r.ok() && r.remaining() != 0) {
    r.fail("end", ("has " + std::to_string(r.remaining()) + " bytes left over").c_str());
  }
  if (!r.ok()) return corrupt(r.error());
  return b;
}

}  // namespace rwd::viewer
