// SPDX-License-Identifier: MIT
#include "rewind/replay/replay_header.h"

#include <vector>

#include "rewind/replay/replay_format.h"
#include "rewind/sim/version.h"

namespace rwd::replay {

v1::ReplayHeader make_replay_header(const game::Game& game, const RecordingSetup& setup) {
  v1::ReplayHeader header;
  header.set_format_version(kFormatVersion);
  header.set_game(std::string(game.name()));
  header.set_player_count(setup.match.player_count);
  header.set_seed(setup.match.seed);
  header.set_tick_rate_hz(setup.tick_rate_hz);
  header.set_window_ticks(setup.window_ticks);
  header.set_server_version(setup.server_version);
  header.set_started_unix_ms(setup.started_unix_ms);
  header.set_keyframe_interval(setup.keyframe_interval);

  header.set_engine(std::string(sim::kEngineName));
  header.set_sim_revision(sim::kSimRevision);
  header.set_rules_version(game.rules_version());
  std::vector<uint8_t> config;
  game.encode_world_config(config);
  header.set_world_config(config.data(), config.size());
  return header;
}

}  // namespace rwd::replay
