// SPDX-License-Identifier: MIT
// Writes view bundles of every built-in game, played natively with
// scripted inputs and recorded as a server records them (each tick's
// inputs and the checksum after it), for the WebAssembly and browser
// tests to re-simulate: the viewer must reach the native checksum at every
// tick. Also writes one bundle with a client's desync report (a body
// nudged after tick 100) and, beside it, the bodies a native comparison
// names, for the browser test to find highlighted.
//
// usage: make_bundles OUT_DIR [TICKS]
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "rewind/game/simulation.h"
#include "rewind/viewer/replay_player.h"
#include "rewind/viewer/view_bundle.h"

namespace {

using namespace rwd;

viewer::ViewBundle play(const std::string& game_name, uint32_t players, Tick ticks) {
  viewer::ViewBundle b;
  b.game = game_name;
  b.setup.player_count = players;
  b.setup.seed = 5;
  for (uint32_t p = 0; p < players; ++p) b.player_names.push_back("bot " + std::to_string(p + 1));
  auto sim = game::Simulation::create(game_name, b.setup);
  if (!sim.ok()) {
    std::fprintf(stderr, "make_bundles: %s\n", sim.status().message().c_str());
    std::exit(1);
  }
  std::vector<rwd::PlayerInput> inputs(players);
  for (Tick t = 0; t < ticks; ++t) {
    for (uint32_t p = 0; p < players; ++p) {
      inputs[p] = rwd::stick_input(
          static_cast<int16_t>(((t / 17 + static_cast<Tick>(p)) % 3 - 1) * 1000),
          static_cast<int16_t>(((t / 41 + 2 * static_cast<Tick>(p)) % 3 - 1) * 800),
          (t + 7 * static_cast<Tick>(p)) % 45 < 3 ? 1u + (t / 90) % 2 : 0u);
    }
    if (rwd::Status status = (*sim)->step(inputs); !status.ok()) {
      std::fprintf(stderr, "make_bundles: %s\n", status.message().c_str());
      std::exit(1);
    }
    b.inputs.insert(b.inputs.end(), inputs.begin(), inputs.end());
    b.checksums.push_back((*sim)->checksum());
    b.substituted_masks.push_back(0);
  }
  return b;
}

void write(const std::string& path, const viewer::ViewBundle& b) {
  std::vector<uint8_t> bytes;
  if (Status s = viewer::encode_view_bundle(b, bytes); !s.ok()) {
    std::fprintf(stderr, "make_bundles: %s\n", s.message().c_str());
    std::exit(1);
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  if (!out.flush()) {
    std::fprintf(stderr, "make_bundles: cannot write %s\n", path.c_str());
    std::exit(1);
  }
  std::printf("%s: %s, %u players, %u ticks\n", path.c_str(), b.game.c_str(), b.setup.player_count,
              b.tick_count());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: make_bundles OUT_DIR [TICKS]\n");
    return 64;
  }
  const std::string dir = argv[1];
  const Tick ticks = argc == 3 ? std::atoi(argv[2]) : 600;
  if (ticks < 120) {
    std::fprintf(stderr, "make_bundles: TICKS must be at least 120\n");
    return 64;
  }
  for (const char* name : {"crates", "arena", "joust"}) {
    write(dir + "/" + name + ".bin", play(name, 3, ticks));
  }
  // A desync: the client's state after tick 100 with one body nudged.
  viewer::ViewBundle b = play("crates", 2, ticks);
  auto client = game::Simulation::create("crates", b.setup);
  for (Tick t = 0; t <= 100; ++t) {
    if (!(*client)
             ->step(
                 std::span<const rwd::PlayerInput>(b.inputs).subspan(static_cast<size_t>(t) * 2, 2))
             .ok()) {
      return 1;
    }
  }
  if (!(*client)->lane().perturb_for_drill()) return 1;
  viewer::ViewDesync d;
  d.tick = 100;
  d.player = 1;
  d.headline = "player 1 desync at tick 100 (a body nudged by make_bundles)";
  (*client)->serialize(d.client_state);
  b.desync = d;
  write(dir + "/desync.bin", b);
  auto player = viewer::ReplayPlayer::create(b);
  auto view = (*player)->open_desync();
  if (!view.ok()) return 1;
  std::ofstream bodies(dir + "/desync_bodies.txt", std::ios::trunc);
  for (uint32_t body : view->bodies) bodies << body << "\n";
  bodies << "fields " << view->differences.size() << "\n";
  return bodies.flush() ? 0 : 1;
}
