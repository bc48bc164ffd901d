// SPDX-License-Identifier: MIT
// The games tag's browser module plays besides Rewind's built-in ones: tag,
// registered under the name tag-server hosts it by.
#include <rewind/client/browser_games.h>

#include "tag_game.h"

rwd::Status rwd::client::register_browser_games() {
  return tag::register_tag_game();
}
