// SPDX-License-Identifier: MIT
// rewind-replay: the run loop of replay_main() on the built-in games.
#include "rewind/tools/replay_main.h"

int main(int argc, char** argv) {
  return rwd::tools::replay_main(argc, argv);
}
