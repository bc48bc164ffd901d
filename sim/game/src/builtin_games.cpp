// SPDX-License-Identifier: MIT
#include <map>
#include <mutex>
#include <string>

#include "rewind/game/arena_game.h"
#include "rewind/game/crates_game.h"
#include "rewind/game/game_registry.h"
#include "rewind/game/joust_game.h"
#include "rewind/game/simulation.h"

namespace rwd::game {
namespace {

// Registered games by name. Keys never move or go away, so the views
// builtin_game_names() returns stay valid for the life of the process.
struct Registry {
  std::mutex mutex;
  std::map<std::string, GameFactory, std::less<>> games;
};

Registry& registry() {
  static Registry instance;
  return instance;
}

bool is_game_name(std::string_view name) {
  if (name.empty() || name.size() > 64) return false;
  for (const char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '.' || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

}  // namespace

std::vector<std::string_view> builtin_game_names() {
  std::vector<std::string_view> names = {"arena", "crates", "joust"};
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  for (const auto& [name, factory] : r.games) names.push_back(name);
  return names;
}

std::unique_ptr<Game> make_builtin_game(std::string_view name) {
  if (name == "crates") return std::make_unique<CratesGame>();
  if (name == "arena") return std::make_unique<ArenaGame>();
  if (name == "joust") return std::make_unique<JoustGame>();
  Registry& r = registry();
  GameFactory factory;
  {
    std::lock_guard lock(r.mutex);
    const auto found = r.games.find(name);
    if (found == r.games.end()) return nullptr;
    factory = found->second;
  }
  return factory();
}

Status register_game(std::string_view name, GameFactory factory) {
  if (!is_game_name(name)) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "game name '" + std::string(name.substr(0, 64)) +
                             "' must be 1 to 64 characters of A-Z a-z 0-9 . _ -");
  }
  if (!factory) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "game '" + std::string(name) + "' has no factory");
  }
  if (name == "crates" || name == "arena" || name == "joust") {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "game '" + std::string(name) + "' is built in");
  }
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  if (!r.games.emplace(std::string(name), std::move(factory)).second) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "game '" + std::string(name) + "' is already registered");
  }
  return Status::Ok();
}

}  // namespace rwd::game
