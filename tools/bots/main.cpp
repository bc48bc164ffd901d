// SPDX-License-Identifier: MIT
// rewind-bots: the run loop of bots_main() on the built-in games.
#include "rewind/tools/bots_main.h"

int main(int argc, char** argv) {
  return rwd::tools::bots_main(argc, argv);
}
