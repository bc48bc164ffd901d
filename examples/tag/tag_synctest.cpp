// SPDX-License-Identifier: MIT
// tag-synctest: a full rewind-synctest that also checks tag.
#include <cstdio>

#include <rewind/tools/synctest_main.h>

#include "tag_game.h"

int main(int argc, char** argv) {
  if (rwd::Status status = tag::register_tag_game(); !status.ok()) {
    std::fprintf(stderr, "tag-synctest: %s\n", status.message().c_str());
    return 1;
  }
  return rwd::tools::synctest_main(argc, argv);
}
