// SPDX-License-Identifier: MIT
// 3D world snapshots with joints: World3D::deserialize must refuse anything
// malformed (a joint naming a missing body, frames that are not unit,
// settings out of range, counts past the bytes) and leave the world as it
// was; what it accepts must re-serialize to the same bytes, step, and the
// state the step reaches must load again.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "fuzz_entries.h"
#include "jointed_world.h"
#include "rewind/sim/world3d.h"

int fuzz_world3d_snapshot_one(const uint8_t* data, size_t size) {
  rwd::sim::World3D world;
  rwd::fuzz::build_jointed_world(world, 0);
  const uint64_t before = world.checksum();
  const rwd::Status status = world.deserialize({data, size});
  if (!status.ok()) {
    if (world.checksum() != before) {
      std::fprintf(stderr, "fuzz_world3d_snapshot: refused input changed the world: %s\n",
                   status.message().c_str());
      std::abort();
    }
    return 0;
  }
  std::vector<uint8_t> again;
  world.serialize(again);
  if (again.size() != size || std::memcmp(again.data(), data, size) != 0) {
    std::fprintf(stderr, "fuzz_world3d_snapshot: accepted snapshot does not re-encode\n");
    std::abort();
  }
  for (int i = 0; i < 3; ++i) world.step();
  world.serialize(again);
  rwd::sim::World3D reader;
  if (rwd::Status s = reader.deserialize(again); !s.ok() || reader.checksum() != world.checksum()) {
    std::fprintf(stderr, "fuzz_world3d_snapshot: a stepped state does not load: %s\n",
                 s.message().c_str());
    std::abort();
  }
  return 0;
}
