// SPDX-License-Identifier: MIT
// tag-server: a full rewind-server that also hosts tag.
#include <cstdio>

#include <rewind/server/server_main.h>

#include "tag_game.h"

int main(int argc, char** argv) {
  if (rwd::Status status = tag::register_tag_game(); !status.ok()) {
    std::fprintf(stderr, "tag-server: %s\n", status.message().c_str());
    return 1;
  }
  return rwd::server::server_main(argc, argv);
}
