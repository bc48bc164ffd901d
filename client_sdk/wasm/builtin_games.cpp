// SPDX-License-Identifier: MIT
// Rewind's own browser client module: the built-in games only.
#include "rewind/client/browser_games.h"

namespace rwd::client {

Status register_browser_games() {
  return Status::Ok();
}

}  // namespace rwd::client
