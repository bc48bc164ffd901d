// SPDX-License-Identifier: MIT
#include "rewind/replay/engine_identity.h"

#include <memory>
#include <span>

#include "rewind/game/simulation.h"
#include "rewind/replay/replay_format.h"
#include "rewind/replay/replay_header.h"
#include "rewind/sim/version.h"

namespace rwd::replay {
namespace {

std::span<const uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const uint8_t*>(s.data()), s.size()};
}

std::string builtin_games() {
  std::string out;
  for (std::string_view name : game::builtin_game_names()) {
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out;
}

void add_config_differences(std::string_view game_name, const std::string& recorded,
                            const std::string& current, std::vector<std::string>& out) {
  auto rec = describe_world_config(game_name, bytes_of(recorded));
  auto cur = describe_world_config(game_name, bytes_of(current));
  if (!rec.ok() || !cur.ok()) {
    out.push_back("world config: the recorded " + std::to_string(recorded.size()) +
                  " bytes do not decode in this build (" +
                  (rec.ok() ? cur.status() : rec.status()).message() + ")");
    return;
  }
  const auto& a = *rec;
  const auto& b = *cur;
  const size_t before = out.size();
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
    if (a[i].second != b[i].second) {
      out.push_back("world config " + a[i].first + ": recorded " + a[i].second + ", this build " +
                    b[i].second);
    }
  }
  if (out.size() == before) {
    out.push_back(
        "world config: the recorded bytes differ from this build's although every "
        "field reads the same");
  }
}

}  // namespace

std::string EngineIdentity::label() const {
  if (!recorded()) {
    return std::string(format_version <= 1 ? "an earlier engine" : "an engine") +
           " that did not record its version (replay format " + std::to_string(format_version) +
           ")";
  }
  std::string out = (engine.empty() ? std::string("an unnamed engine") : engine) + " r" +
                    std::to_string(sim_revision);
  if (rules_version) {
    out += " (" + game + " rules " + std::to_string(*rules_version) + ")";
  } else {
    out += " (no game \"" + game + "\")";
  }
  return out;
}

std::string VersionCheck::recorded_label() const {
  const bool other_config = recorded.recorded() && this_build.rules_version &&
                            recorded.world_config != this_build.world_config;
  return recorded.label() + (other_config ? " with another world config" : "");
}

EngineIdentity recorded_identity(const v1::ReplayHeader& header) {
  EngineIdentity id;
  id.format_version = header.format_version();
  id.game = header.game();
  // Format 1 has no identity; whatever such a file holds in these fields
  // was not written by a writer that knew their meaning.
  if (header.format_version() >= 2) {
    id.engine = header.engine();
    id.sim_revision = header.sim_revision();
    id.rules_version = header.rules_version();
    id.world_config = header.world_config();
  }
  return id;
}

EngineIdentity this_build_identity(std::string_view game_name) {
  if (std::unique_ptr<game::Game> g = game::make_builtin_game(game_name)) {
    return recorded_identity(make_replay_header(*g, RecordingSetup{}));
  }
  EngineIdentity id;
  id.format_version = kFormatVersion;
  id.engine = std::string(sim::kEngineName);
  id.sim_revision = sim::kSimRevision;
  id.game = std::string(game_name);
  return id;
}

VersionCheck check_versions(const v1::ReplayHeader& header) {
  VersionCheck check;
  check.recorded = recorded_identity(header);
  check.this_build = this_build_identity(header.game());
  const EngineIdentity& rec = check.recorded;
  const EngineIdentity& now = check.this_build;
  std::vector<std::string>& out = check.differences;

  if (rec.format_version > kFormatVersion) {
    out.push_back("replay format: recorded version " + std::to_string(rec.format_version) +
                  ", this build reads " + readable_formats());
  }
  if (!rec.recorded()) {
    out.push_back("engine: not recorded (replay format " + std::to_string(rec.format_version) +
                  "), this build " + now.engine + " r" + std::to_string(now.sim_revision));
  } else {
    if (rec.engine != now.engine) {
      out.push_back("engine: recorded \"" + rec.engine + "\", this build \"" + now.engine + "\"");
    }
    if (rec.sim_revision != now.sim_revision) {
      out.push_back("sim revision: recorded " + std::to_string(rec.sim_revision) + ", this build " +
                    std::to_string(now.sim_revision));
    }
  }
  if (!now.rules_version) {
    out.push_back("game: this build has no game \"" + rec.game + "\" (it has: " + builtin_games() +
                  ")");
  } else if (rec.recorded()) {
    if (rec.rules_version != now.rules_version) {
      out.push_back(rec.game + " rules version: recorded " +
                    std::to_string(rec.rules_version.value_or(0)) + ", this build " +
                    std::to_string(*now.rules_version));
    }
    if (rec.world_config != now.world_config) {
      add_config_differences(rec.game, rec.world_config, now.world_config, out);
    }
  }
  return check;
}

Result<std::vector<std::pair<std::string, std::string>>> describe_world_config(
    std::string_view game_name, std::span<const uint8_t> bytes) {
  std::unique_ptr<game::Game> g = game::make_builtin_game(game_name);
  if (!g) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "this build has no game \"" + std::string(game_name) + "\"");
  }
  return g->describe_world_config(bytes);
}

}  // namespace rwd::replay
