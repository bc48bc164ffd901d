// SPDX-License-Identifier: MIT
// rewind-server: hosts the built-in games (and any a program built on
// server_main() registers).
#include "rewind/server/server_main.h"

int main(int argc, char** argv) {
  return rwd::server::server_main(argc, argv);
}
