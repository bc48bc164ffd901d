// SPDX-License-Identifier: MIT
// Serialized simulations arrive from outside twice over: resync snapshots
// (server -> client) and desync dumps (client -> server, untrusted). The
// parser must refuse anything malformed and leave the simulation exactly as
// it was; whatever it accepts must step, checksum and re-serialize to the
// same bytes, and the state the step then reaches must load again (the state
// rule holds both ways). The same bytes also feed the world config codec,
// whose accepted inputs must re-encode to themselves.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "fuzz_entries.h"
#include "rewind/game/simulation.h"
#include "rewind/sim/world3d.h"

namespace {

void fuzz_config_codec(const uint8_t* data, size_t size) {
  auto config = rwd::sim::World3D::decode_config({data, size});
  if (!config.ok()) return;
  std::vector<uint8_t> again;
  rwd::sim::World3D::encode_config(*config, again);
  if (again.size() != size || std::memcmp(again.data(), data, size) != 0) {
    std::fprintf(stderr, "fuzz_sim_snapshot: accepted config does not re-encode\n");
    std::abort();
  }
}

}  // namespace

int fuzz_sim_snapshot_one(const uint8_t* data, size_t size) {
  fuzz_config_codec(data, size);
  static const std::unique_ptr<rwd::game::Simulation> pristine = [] {
    auto sim = rwd::game::Simulation::create("crates", {4, 7});
    return sim.ok() ? std::move(*sim) : nullptr;
  }();
  if (!pristine) std::abort();
  auto sim = std::move(*rwd::game::Simulation::create("crates", {4, 7}));
  const uint64_t before = sim->checksum();
  const rwd::Status status = sim->deserialize({data, size});
  if (!status.ok()) {
    if (sim->checksum() != before || sim->tick() != 0) {
      std::fprintf(stderr, "fuzz_sim_snapshot: refused input changed the simulation: %s\n",
                   status.message().c_str());
      std::abort();  // must be untouched
    }
    return 0;
  }
  // Accepted: a canonical round trip, and the world must survive a step.
  std::vector<uint8_t> again;
  sim->serialize(again);
  auto copy = std::move(*rwd::game::Simulation::create("crates", {4, 7}));
  if (rwd::Status again_status = copy->deserialize(again);
      !again_status.ok() || copy->checksum() != sim->checksum()) {
    std::fprintf(stderr, "fuzz_sim_snapshot: accepted snapshot does not round-trip: %s\n",
                 again_status.message().c_str());
    std::abort();
  }
  std::vector<rwd::PlayerInput> inputs(4);
  // A state the game accepts (validate_state) may still be one its rules
  // refuse to step: that is an error returned, not a crash.
  if (!sim->step(inputs).ok()) return 0;
  sim->serialize(again);
  if (rwd::Status stepped = copy->deserialize(again);
      !stepped.ok() || copy->checksum() != sim->checksum()) {
    std::fprintf(stderr, "fuzz_sim_snapshot: a state the step reached does not load: %s\n",
                 stepped.message().c_str());
    std::abort();
  }
  return 0;
}
