// SPDX-License-Identifier: MIT
// Match settings from an allocation's rewind.dev/* annotations and labels:
// each setting's range, the precedence of annotations, and that a refused
// allocation leaves the configuration as it was.
#include "rewind/server/agones_match_settings.h"

#include <gtest/gtest.h>

#include <string>

namespace rwd::server {
namespace {

AgonesGameServer allocation(std::map<std::string, std::string> annotations,
                            std::map<std::string, std::string> labels = {}) {
  AgonesGameServer gs;
  gs.state = "Allocated";
  gs.annotations = std::move(annotations);
  gs.labels = std::move(labels);
  return gs;
}

TEST(AgonesMatchSettings, EverySettingApplies) {
  MatchConfig match;
  auto applied = apply_agones_match_settings(allocation({{"rewind.dev/game", "crates"},
                                                         {"rewind.dev/players", "4"},
                                                         {"rewind.dev/spectators", "2"},
                                                         {"rewind.dev/tick-rate", "30"},
                                                         {"rewind.dev/window", "12"},
                                                         {"rewind.dev/ticks", "1800"},
                                                         {"rewind.dev/seed", "9223372036854775807"},
                                                         {"rewind.dev/match-id", "duel-7"},
                                                         {"rewind.dev/join-timeout", "12.5"},
                                                         {"rewind.dev/peer-timeout", "3"}}),
                                             &match);
  ASSERT_TRUE(applied.ok()) << applied.status().message();
  EXPECT_EQ(match.game, "crates");
  EXPECT_EQ(match.players, 4u);
  EXPECT_EQ(match.max_spectators, 2u);
  EXPECT_EQ(match.tick_rate_hz, 30u);
  EXPECT_EQ(match.window_ticks, 12);
  EXPECT_EQ(match.max_ticks, 1800);
  EXPECT_EQ(match.seed, 9223372036854775807ull);
  EXPECT_EQ(match.match_id, "duel-7");
  EXPECT_EQ(match.join_timeout_s, 12.5);
  EXPECT_EQ(match.peer_timeout_s, 3.0);
  EXPECT_NE(applied->find("players=4 (annotation)"), std::string::npos) << *applied;
}

TEST(AgonesMatchSettings, NothingToApply) {
  MatchConfig match;
  match.players = 3;
  auto applied = apply_agones_match_settings(
      allocation({{"agones.dev/ready-container-id", "x"}}, {{"app", "rewind"}}), &match);
  ASSERT_TRUE(applied.ok());
  EXPECT_EQ(*applied, "");
  EXPECT_EQ(match.players, 3u);
}

TEST(AgonesMatchSettings, AnAnnotationWinsOverALabel) {
  MatchConfig match;
  auto applied = apply_agones_match_settings(
      allocation({{"rewind.dev/players", "5"}},
                 {{"rewind.dev/players", "6"}, {"rewind.dev/ticks", "60"}}),
      &match);
  ASSERT_TRUE(applied.ok()) << applied.status().message();
  EXPECT_EQ(match.players, 5u);
  EXPECT_EQ(match.max_ticks, 60);
  EXPECT_EQ(*applied, "players=5 (annotation), ticks=60 (label)");
}

// Refused with `message`; the configuration keeps every earlier value.
void expect_refused(std::map<std::string, std::string> annotations, const std::string& message) {
  MatchConfig match;
  match.players = 3;
  match.max_ticks = 77;
  const MatchConfig before = match;
  auto applied = apply_agones_match_settings(allocation(std::move(annotations)), &match);
  ASSERT_FALSE(applied.ok());
  EXPECT_EQ(applied.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(applied.status().message(), message);
  EXPECT_EQ(match.players, before.players);
  EXPECT_EQ(match.max_ticks, before.max_ticks);
  EXPECT_EQ(match.game, before.game);
  EXPECT_EQ(match.match_id, before.match_id);
}

TEST(AgonesMatchSettings, BadValuesAreRefused) {
  expect_refused({{"rewind.dev/players", "99"}}, "rewind.dev/players: '99' is outside [1, 32]");
  expect_refused({{"rewind.dev/players", "0"}}, "rewind.dev/players: '0' is outside [1, 32]");
  expect_refused({{"rewind.dev/players", "four"}}, "rewind.dev/players: 'four' is not an integer");
  expect_refused({{"rewind.dev/players", "-1"}}, "rewind.dev/players: '-1' is not an integer");
  expect_refused({{"rewind.dev/players", " 4"}}, "rewind.dev/players: ' 4' is not an integer");
  expect_refused({{"rewind.dev/players", ""}}, "rewind.dev/players: '' is not an integer");
  expect_refused({{"rewind.dev/ticks", "99999999999999999999"}},
                 "rewind.dev/ticks: '99999999999999999999' is outside [0, 2147483648]");
  expect_refused({{"rewind.dev/tick-rate", "1001"}},
                 "rewind.dev/tick-rate: '1001' is outside [1, 1000]");
  expect_refused({{"rewind.dev/join-timeout", "nan"}},
                 "rewind.dev/join-timeout: 'nan' is not a number of seconds");
  expect_refused({{"rewind.dev/peer-timeout", "0"}},
                 "rewind.dev/peer-timeout: '0' is outside [0.1, 3600] s");
  expect_refused({{"rewind.dev/match-id", "two words"}},
                 "rewind.dev/match-id: 'two words' must be 1-64 characters of A-Z a-z 0-9 . _ -");
  expect_refused({{"rewind.dev/match-id", ""}},
                 "rewind.dev/match-id: '' must be 1-64 characters of A-Z a-z 0-9 . _ -");
  expect_refused({{"rewind.dev/match-id", "a\nb"}},
                 "rewind.dev/match-id: 'a?b' must be 1-64 characters of A-Z a-z 0-9 . _ -");
}

TEST(AgonesMatchSettings, UnknownSettingsAreRefused) {
  expect_refused({{"rewind.dev/player", "4"}},
                 "unknown setting rewind.dev/player (annotation); known under rewind.dev/: game, "
                 "join-timeout, match-id, peer-timeout, players, seed, spectators, start-players, "
                 "tick-rate, ticks, window");
}

TEST(AgonesMatchSettings, TheWholeConfigurationIsValidated) {
  expect_refused(
      {{"rewind.dev/game", "chess"}, {"rewind.dev/players", "4"}},
      "the allocation's match settings: unknown game 'chess' (known: arena crates joust)");
  expect_refused({{"rewind.dev/players", "32"}, {"rewind.dev/spectators", "63"}},
                 "the allocation's match settings: players + spectators must be at most 64");
}

}  // namespace
}  // namespace rwd::server
