// SPDX-License-Identifier: MIT
#include "rewind/game/crates_game.h"
#include "rewind/game/simulation.h"

namespace rwd::game {

std::vector<std::string_view> builtin_game_names() {
  return {"crates"};
}

std::unique_ptr<Game> make_builtin_game(std::string_view name) {
  if (name == "crates") return std::make_unique<CratesGame>();
  return nullptr;
}

}  // namespace rwd::game
