// SPDX-License-Identifier: MIT
// tag-bots: a full rewind-bots that also plays tag with its own bots.
#include <cstdio>

#include <rewind/tools/bots_main.h>

#include "tag_game.h"

int main(int argc, char** argv) {
  if (rwd::Status status = tag::register_tag_game(); !status.ok()) {
    std::fprintf(stderr, "tag-bots: %s\n", status.message().c_str());
    return 1;
  }
  return rwd::tools::bots_main(argc, argv);
}
