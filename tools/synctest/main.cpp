// SPDX-License-Identifier: MIT
// rewind-synctest: the sync test on the built-in games (and any a program
// built on synctest_main() registers).
#include "rewind/tools/synctest_main.h"

int main(int argc, char** argv) {
  return rwd::tools::synctest_main(argc, argv);
}
