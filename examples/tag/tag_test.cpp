// SPDX-License-Identifier: MIT
// tag's rules, checked on a headless simulation: "it" changes hands, points
// add up, and the state a checksum covers round-trips.
#include <cstdio>
#include <cstring>
#include <vector>

#include <rewind/game/simulation.h>
#include <rewind/game/sync_test.h>

#include "tag_game.h"

namespace {

int failures = 0;

void expect(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "FAIL: %s\n", what);
    ++failures;
  }
}

tag::TagState state_of(const rwd::game::Simulation& sim) {
  tag::TagState state;
  std::memcpy(&state, sim.game_state().data(), sizeof state);
  return state;
}

}  // namespace

int main() {
  expect(tag::register_tag_game().ok(), "tag registers");
  expect(!tag::register_tag_game().ok(), "a second registration is refused");

  auto sim = rwd::game::Simulation::create("tag", {4, 7});
  expect(sim.ok(), "a tag match is created by name");
  if (!sim.ok()) return 1;
  const rwd::game::Game& game = (*sim)->game();
  const uint32_t first_it = state_of(**sim).it;
  expect(first_it < 4, "'it' is a player");

  std::vector<rwd::PlayerInput> inputs(4);
  const int ticks = 1800;
  for (rwd::Tick t = 0; t < ticks; ++t) {
    for (uint32_t p = 0; p < 4; ++p) inputs[p] = game.bot_input(7, p, t);
    if (rwd::Status status = (*sim)->step(inputs); !status.ok()) {
      std::fprintf(stderr, "FAIL: %s\n", status.message().c_str());
      return 1;
    }
  }
  const tag::TagState end = state_of(**sim);
  std::printf("after %d ticks: %u tags; points", ticks, end.tags);
  uint32_t total = 0;
  for (uint32_t p = 0; p < 4; ++p) {
    std::printf(" %u", end.points[p]);
    total += end.points[p];
  }
  std::printf("\n");
  // Three of four players score each tick.
  expect(total == 3u * ticks, "three points a tick in all");
  expect(end.tags > 0, "the bots tag each other within 30 s");

  // The sync test: rollback and re-simulation every tick, state round trips
  // and a second instance must all agree with the first run.
  rwd::game::SyncTestOptions options;
  options.ticks = 300;
  auto report = rwd::game::run_sync_test("tag", {4, 7}, options);
  expect(report.ok(), "the sync test runs on tag");
  if (report.ok() && report->failure)
    std::fprintf(stderr, "%s\n", report->failure->describe().c_str());
  expect(report.ok() && !report->failure, "tag passes the sync test");

  if (failures == 0) std::printf("tag_test: all checks passed\n");
  return failures == 0 ? 0 : 1;
}
