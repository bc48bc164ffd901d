// SPDX-License-Identifier: MIT
#include "rewind/tools/synctest_main.h"

#include <cinttypes>
#include <cstdio>
#include <string>

#include "rewind/cli/flag_parser.h"
#include "rewind/game/simulation.h"
#include "rewind/game/sync_test.h"

namespace rwd::tools {

int synctest_main(int argc, const char* const* argv) {
  std::string game = "crates";
  int64_t players = 2, seed = 1, ticks = 600, distance = 2, round_trip_every = 1, input_seed = 1;
  bool second_instance = true;
  cli::FlagParser flags(
      "rewind-synctest", "rewind-synctest [flags]",
      "Checks that a game's own code is deterministic before it meets players: plays a match\n"
      "alone with scripted inputs and, after every tick, rolls back and re-simulates the last\n"
      "ticks, reloads the state from its bytes and compares a second copy of the match built\n"
      "on its own. Names the first tick, check and field that differ.");
  flags.add_string("game", &game, "the game to test (built-in or registered)");
  flags.add_int("players", &players, 1, game::kMaxPlayers, "players in the match");
  flags.add_int("seed", &seed, 0, INT64_MAX, "the match's seed");
  flags.add_int("ticks", &ticks, 1, 1'000'000, "ticks to play");
  flags.add_int("check-distance", &distance, 1, 64,
                "ticks rolled back and re-simulated after every tick");
  flags.add_int("round-trip-every", &round_trip_every, 0, 1'000'000,
                "serialize and reload the state every this many ticks (0 = never)");
  flags.add_bool("second-instance", &second_instance,
                 "step a second copy of the match, built on its own, beside the first "
                 "(--second-instance=false to skip)");
  flags.add_int("input-seed", &input_seed, 0, INT64_MAX, "seeds the scripted inputs");
  if (Status status = flags.parse(argc, argv); !status.ok()) {
    std::fprintf(stderr, "rewind-synctest: %s\n", status.message().c_str());
    return cli::kExitUsage;
  }
  if (flags.help_requested()) {
    std::fputs(flags.help_text().c_str(), stdout);
    return 0;
  }
  game::SyncTestOptions options;
  options.ticks = static_cast<uint32_t>(ticks);
  options.check_distance = static_cast<uint32_t>(distance);
  options.round_trip_every = static_cast<uint32_t>(round_trip_every);
  options.second_instance = second_instance;
  options.input_seed = static_cast<uint64_t>(input_seed);
  const game::MatchSetup setup{static_cast<uint32_t>(players), static_cast<uint64_t>(seed)};
  auto report = game::run_sync_test(game, setup, options);
  if (!report.ok()) {
    std::fprintf(stderr, "rewind-synctest: %s\n", report.status().message().c_str());
    return report.status().code() == ErrorCode::kInvalidArgument ? cli::kExitUsage : 1;
  }
  if (report->failure) {
    const game::SyncTestFailure& f = *report->failure;
    std::printf("synctest %s: NOT DETERMINISTIC: %s\n", game.c_str(), f.describe().c_str());
    for (const rwd::FieldDifference& d : f.fields) {
      std::printf("  body %u %s: %.9g, expected %.9g\n", d.body_index, d.field.c_str(), d.actual,
                  d.expected);
    }
    return 1;
  }
  std::printf("synctest %s: deterministic: %u ticks of %u players, %" PRIu64
              " re-simulated after %u-tick rollbacks, %" PRIu64
              " round trips%s; final checksum "
              "%016" PRIx64 "\n",
              game.c_str(), report->ticks, setup.player_count, report->resimulated_ticks,
              options.check_distance, report->round_trips,
              second_instance ? ", a second instance beside" : "", report->final_checksum);
  return 0;
}

}  // namespace rwd::tools
