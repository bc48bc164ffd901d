// SPDX-License-Identifier: MIT
#include "rewind/viewer/view_bundle.h"

#include <cstring>
#include <string_view>

namespace rwd::viewer {
namespace {

constexpr char kMagic[8] = {'R', 'W', 'D', 'V', 'I', 'E', 'W', '1'};

class Writer {
 public:
  explicit Writer(std::vector<uint8_t>& out) : out_(out) {}
  void put(uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  void bytes(std::span<const uint8_t> b) {
    put(b.size(), 4);
    out_.insert(out_.end(), b.begin(), b.end());
  }
  void str(std::string_view s) { bytes({reinterpret_cast<const uint8_t*>(s.data()), s.size()}); }

 private:
  std::vector<uint8_t>& out_;
};

/// Bounds-checked reads; the first failure is kept with its offset and
/// every later read gives zeros.
class Reader {
 public:
  Reader(std::span<const uint8_t> bytes, size_t start) : bytes_(bytes), pos_(start) {}
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  size_t remaining() const { return bytes_.size() - pos_; }
  size_t offset() const { return pos_; }

  uint64_t get(int n, const char* what) {
    if (!ok()) return 0;
    if (remaining() < static_cast<size_t>(n)) {
      fail(what, "runs past the end");
      return 0;
    }
    uint64_t v = 0;
    for (int i = 0; i < n; ++i) v |= uint64_t{bytes_[pos_ + static_cast<size_t>(i)]} << (8 * i);
    pos_ += static_cast<size_t>(n);
    return v;
  }
  std::span<const uint8_t> run(uint32_t bound, const char* what) {
    const uint64_t n = get(4, what);
    if (!ok()) return {};
    if (n > bound) {
      fail(what,
           ("is " + std::to_string(n) + " bytes, more than " + std::to_string(bound)).c_str());
      return {};
    }
    if (remaining() < n) {
      fail(what, "runs past the end");
      return {};
    }
    const auto out = bytes_.subspan(pos_, static_cast<size_t>(n));
    pos_ += static_cast<size_t>(n);
    return out;
  }
  std::string str(uint32_t bound, const char* what) {
    const auto b = run(bound, what);
    return {reinterpret_cast<const char*>(b.data()), b.size()};
  }
  void fail(const char* what, const char* problem) {
    if (ok()) error_ = std::string(what) + " at byte " + std::to_string(pos_) + " " + problem;
  }

 private:
  std::span<const uint8_t> bytes_;
  size_t pos_ = 0;
  std::string error_;
};

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
  if (b.checksums.size() > kViewMaxTicks) return invalid("too many ticks");
  if (b.substituted_masks.size() != b.checksums.size() ||
      b.inputs.size() != b.checksums.size() * b.setup.player_count) {
    return invalid("inputs, checksums and masks must cover the same ticks");
  }
  for (const game::PlayerInput& input : b.inputs) {
    if (!game::is_valid(input)) return invalid("an input axis is out of range");
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
  bytes.insert(bytes.end(), kMagic, kMagic + sizeof kMagic);
  w.put(kViewBundleVersion, 4);
  w.str(b.game);
  w.put(b.setup.player_count, 4);
  w.put(b.setup.seed, 8);
  w.put(b.tick_rate_hz, 4);
  w.put(b.identity_matches ? 1 : 0, 1);
  w.str(b.identity_note);
  w.put(b.player_names.size(), 4);
  for (const std::string& name : b.player_names) w.str(name);
  w.put(b.checksums.size(), 4);
  const uint32_t players = b.setup.player_count;
  for (size_t t = 0; t < b.checksums.size(); ++t) {
    w.put(b.checksums[t], 8);
    w.put(b.substituted_masks[t], 8);
    for (uint32_t p = 0; p < players; ++p) {
      const game::PlayerInput& in = b.inputs[t * players + p];
      w.put(static_cast<uint16_t>(in.axis_x), 2);
      w.put(static_cast<uint16_t>(in.axis_y), 2);
      w.put(in.buttons, 4);
    }
  }
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
  if (r.ok() && version != kViewBundleVersion) {
    return corrupt("version " + std::to_string(version) + " (this build reads " +
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
  const uint64_t ticks = r.get(4, "tick count");
  if (r.ok() && ticks > kViewMaxTicks) r.fail("tick count", "is beyond the bound");
  // Each tick takes 16 + 8 * players bytes: refuse a count the bytes
  // cannot hold before reserving for it.
  if (r.ok() && r.remaining() / (16 + 8 * players) < ticks) r.fail("ticks", "run past the end");
  if (r.ok()) {
    b.checksums.reserve(ticks);
    b.substituted_masks.reserve(ticks);
    b.inputs.reserve(ticks * players);
  }
  for (uint64_t t = 0; r.ok() && t < ticks; ++t) {
    b.checksums.push_back(r.get(8, "checksum"));
    b.substituted_masks.push_back(r.get(8, "substituted mask"));
    for (uint64_t p = 0; p < players; ++p) {
      game::PlayerInput in;
      in.axis_x = static_cast<int16_t>(static_cast<uint16_t>(r.get(2, "axis x")));
      in.axis_y = static_cast<int16_t>(static_cast<uint16_t>(r.get(2, "axis y")));
      in.buttons = static_cast<uint32_t>(r.get(4, "buttons"));
      if (r.ok() && !game::is_valid(in)) r.fail("input", "has an axis out of range");
      b.inputs.push_back(in);
    }
  }
  const uint64_t has_desync = r.get(1, "desync flag");
  if (r.ok() && has_desync > 1) r.fail("desync flag", "is neither 0 nor 1");
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
