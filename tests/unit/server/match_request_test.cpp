// SPDX-License-Identifier: MIT
#include "rewind/server/match_request.h"

#include <gtest/gtest.h>

namespace rwd::server {
namespace {

TEST(MatchRequest, ReadsEveryKeyOverTheDefaults) {
  MatchConfig defaults;
  defaults.players = 4;
  auto request = parse_match_request(
      "id=duel-7&game=crates&players=2&spectators=3&tick_rate=30&window=6&ticks=900&seed=42&"
      "join_timeout=12.5&peer_timeout=2&port=7800",
      defaults);
  ASSERT_TRUE(request.ok()) << request.status().message();
  const MatchConfig& m = request->match;
  EXPECT_EQ(m.match_id, "duel-7");
  EXPECT_EQ(m.players, 2u);
  EXPECT_EQ(m.max_spectators, 3u);
  EXPECT_EQ(m.tick_rate_hz, 30u);
  EXPECT_EQ(m.window_ticks, 6);
  EXPECT_EQ(m.max_ticks, 900);
  EXPECT_EQ(m.seed, 42u);
  EXPECT_DOUBLE_EQ(m.join_timeout_s, 12.5);
  EXPECT_DOUBLE_EQ(m.peer_timeout_s, 2.0);
  EXPECT_EQ(request->port, 7800);
  auto late = parse_match_request("players=4&start_players=2", defaults);
  ASSERT_TRUE(late.ok()) << late.status().message();
  EXPECT_EQ(late->match.start_players, 2u);
  EXPECT_TRUE(late->match.late_join());
}

TEST(MatchRequest, AnEmptyQueryIsTheDefaults) {
  MatchConfig defaults;
  defaults.players = 3;
  auto request = parse_match_request("", defaults);
  ASSERT_TRUE(request.ok());
  EXPECT_EQ(request->match.players, 3u);
  EXPECT_EQ(request->port, 0);
  EXPECT_TRUE(parse_match_request("&&players=2&", defaults).ok());
}

TEST(MatchRequest, RefusesWhatAFlagWouldRefuse) {
  const MatchConfig defaults;
  for (const std::string& query : std::initializer_list<std::string>{
           "players=0", "players=33", "players=2x", "players=", "players", "tick_rate=0",
           "window=121", "ticks=-1", "port=65536", "join_timeout=0", "peer_timeout=nan",
           "game=chess", "id=has%20space", "id=a/b", "colour=red", "players=2&players=3",
           "spectators=64&players=1", "players=2&start_players=3", "id=" + std::string(65, 'x')}) {
    auto request = parse_match_request(query, defaults);
    EXPECT_FALSE(request.ok()) << query;
    if (!request.ok()) {
      EXPECT_FALSE(request.status().message().empty());
    }
  }
  EXPECT_FALSE(parse_match_request(std::string(1025, 'a'), defaults).ok());
}

TEST(MatchRequest, ErrorsNameTheKey) {
  auto request = parse_match_request("players=2&window=500", MatchConfig{});
  ASSERT_FALSE(request.ok());
  EXPECT_NE(request.status().message().find("window"), std::string::npos);
}

}  // namespace
}  // namespace rwd::server
