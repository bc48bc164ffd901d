// SPDX-License-Identifier: MIT
#pragma once
// Which engine, game rules and world tuning produced a replay, and whether
// this build runs the same ones. Builds with a different sim revision, rules
// version or world config promise nothing about re-simulating each other's
// matches, so the verifier compares identities before it compares
// checksums.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/v1/replay.pb.h"

namespace rwd::replay {

/// The identity a replay header records (format 2 on), or the one this
/// build would record for a game.
struct EngineIdentity {
  uint32_t format_version = 0;  ///< replay format of the file (this build: kFormatVersion)
  std::string engine;           ///< "rewind-sim"; empty when not recorded
  uint32_t sim_revision = 0;    ///< 0 when not recorded
  std::string game;
  /// Unset when not recorded, or when this build has no such game.
  std::optional<uint32_t> rules_version;
  /// The game's world config in its lane's encoding (Game::encode_world_config());
  /// empty when not recorded or no such game.
  std::string world_config;

  /// True when the engine and revision are known (format 2 on).
  bool recorded() const { return sim_revision != 0; }
  /// "rewind-sim r2 (crates rules 2)", or for a file without an identity
  /// "an earlier engine that did not record its version (replay format 1)".
  std::string label() const;
};

/// What `header` records.
EngineIdentity recorded_identity(const v1::ReplayHeader& header);
/// What this build runs for `game` (no rules version or world config when
/// the game is not built in).
EngineIdentity this_build_identity(std::string_view game);

/// A recorded identity against this build's.
struct VersionCheck {
  EngineIdentity recorded;
  EngineIdentity this_build;
  /// One line per difference, naming the recorded value and this build's
  /// ("sim revision: recorded 1, this build 2"); empty when they match.
  std::vector<std::string> differences;

  bool matches() const { return differences.empty(); }
  /// recorded.label(), plus " with another world config" when only the
  /// config tells the two apart in the labels.
  std::string recorded_label() const;
};

/// Compares the identity in `header` with this build's for the same game:
/// replay format, engine name, sim revision, game, rules version and the
/// world config bytes (differing configs are named field by field).
VersionCheck check_versions(const v1::ReplayHeader& header);

/// World config bytes that a replay of `game_name` records, as readable
/// (name, value) pairs in encoding order, as the game's lane describes them
/// (for the 3D lane: names as in sim::WorldConfig, "gravity",
/// "(0, -9.81, 0) m/s^2"). kInvalidArgument when this build has no such
/// game; kCorrupt when its lane cannot decode the bytes.
Result<std::vector<std::pair<std::string, std::string>>> describe_world_config(
    std::string_view game_name, std::span<const uint8_t> bytes);

}  // namespace rwd::replay
