// SPDX-License-Identifier: MIT
// tag-replay: a full rewind-replay that also verifies tag replays.
#include <cstdio>

#include <rewind/tools/replay_main.h>

#include "tag_game.h"

int main(int argc, char** argv) {
  if (rwd::Status status = tag::register_tag_game(); !status.ok()) {
    std::fprintf(stderr, "tag-replay: %s\n", status.message().c_str());
    return 1;
  }
  return rwd::tools::replay_main(argc, argv);
}
