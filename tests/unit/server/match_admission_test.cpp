// SPDX-License-Identifier: MIT
// Who takes which seat: the admission's decisions on their own, without a
// host, a simulation or a socket.
#include <gtest/gtest.h>

#include "rewind/server/match_admission.h"

namespace rwd::server {
namespace {

using Kind = MatchAdmission::Decision::Kind;

TimePoint time_at(double seconds) {
  return TimePoint{} +
         std::chrono::duration_cast<TimePoint::duration>(std::chrono::duration<double>(seconds));
}

Endpoint client_address(uint16_t port) {
  return {asio::ip::make_address("10.0.0.7"), port};
}

v1::JoinRequest join_request(uint64_t nonce, bool spectator = false,
                             const std::string& game = "crates") {
  v1::JoinRequest join;
  join.set_nonce(nonce);
  join.set_game(game);
  join.set_spectator(spectator);
  join.set_client_name("client " + std::to_string(nonce));
  return join;
}

struct Tokenless {
  MatchConfig config = [] {
    MatchConfig c;
    c.players = 2;
    c.max_spectators = 1;
    return c;
  }();
  MatchSeats seats{config.players, config.max_spectators};
  MatchAdmission admission{config, seats};
  Admission answered_cookie;

  MatchAdmission::Decision join(uint64_t nonce, uint16_t port,
                                MatchPhase phase = MatchPhase::kLobby, bool spectator = false,
                                double t = 0.0) {
    return admission.admit(join_request(nonce, spectator), client_address(port), phase,
                           answered_cookie, time_at(t));
  }
};

TEST(MatchAdmission, TheLobbyFillsSlotsInOrderThenRefuses) {
  Tokenless match;
  const auto first = match.join(1, 5001);
  ASSERT_EQ(first.kind, Kind::kSeated);
  EXPECT_EQ(first.seat, 0u);
  EXPECT_FALSE(first.rejoin);
  EXPECT_EQ(match.seats[0].name, "client 1");
  EXPECT_TRUE(match.seats[0].connection.has_value());
  EXPECT_EQ(match.join(2, 5002).seat, 1u);
  const auto full = match.join(3, 5003);
  EXPECT_EQ(full.kind, Kind::kRejected);
  EXPECT_EQ(full.reason, "match is full");
  EXPECT_EQ(match.seats.players_joined(), 2u);
}

TEST(MatchAdmission, ARepeatedRequestIsAnsweredAgainAndAnotherFromTheSameAddressRefused) {
  Tokenless match;
  const auto first = match.join(7, 5001);
  const uint64_t connection = match.seats[0].connection->connection_id();
  const auto again = match.join(7, 5001);
  EXPECT_EQ(again.kind, Kind::kAnswerAgain);
  EXPECT_EQ(again.seat, 0u);
  EXPECT_EQ(match.seats[0].connection->connection_id(), connection);  // nothing changed
  const auto other = match.join(8, 5001);
  EXPECT_EQ(other.kind, Kind::kRejected);
  EXPECT_EQ(other.reason, "this address already holds seat 0");
  EXPECT_EQ(first.kind, Kind::kSeated);
}

TEST(MatchAdmission, AnotherGameIsRefusedByName) {
  Tokenless match;
  const auto decision =
      match.admission.admit(join_request(1, false, "arena"), client_address(5001),
                            MatchPhase::kLobby, match.answered_cookie, time_at(0));
  EXPECT_EQ(decision.kind, Kind::kRejected);
  EXPECT_EQ(decision.reason, "this server hosts 'crates', not 'arena'");
  EXPECT_EQ(match.seats.players_joined(), 0u);
}

TEST(MatchAdmission, SpectatorsTakeTheirOwnSeatsUntilNoneIsFree) {
  Tokenless match;
  const auto watcher = match.join(1, 6001, MatchPhase::kLobby, true);
  ASSERT_EQ(watcher.kind, Kind::kSeated);
  EXPECT_EQ(watcher.seat, 2u);  // players + 0
  EXPECT_FALSE(match.seats.is_player(watcher.seat));
  const auto second = match.join(2, 6002, MatchPhase::kRunning, true);
  EXPECT_EQ(second.kind, Kind::kRejected);
  EXPECT_EQ(second.reason, "no spectator seat is free");
  // Once the match is over nobody is seated.
  match.seats[2].connected = false;
  EXPECT_EQ(match.join(3, 6003, MatchPhase::kClosing, true).kind, Kind::kRejected);
}

TEST(MatchAdmission, MidMatchAFreedSlotIsTakenAndItsProgressStartsOver) {
  Tokenless match;
  match.join(1, 5001);
  match.join(2, 5002);
  EXPECT_EQ(match.join(3, 5003, MatchPhase::kRunning).reason, "match already running");
  Seat& gone = match.seats[1];
  gone.final_seen = 400;
  gone.final_sent = 410;
  gone.left = true;
  const auto rejoin = match.join(3, 5003, MatchPhase::kRunning, false, 9.0);
  ASSERT_EQ(rejoin.kind, Kind::kSeated);
  EXPECT_EQ(rejoin.seat, 1u);
  EXPECT_TRUE(rejoin.rejoin);
  EXPECT_EQ(gone.final_seen, kNoTick);
  EXPECT_EQ(gone.final_sent, kNoTick);
  EXPECT_FALSE(gone.left);
  EXPECT_EQ(gone.endpoint, client_address(5003));
  EXPECT_EQ(gone.last_receive, time_at(9.0));
}

TEST(MatchAdmission, LateJoinersTakeNeverTakenSlotsFirst) {
  Tokenless match;
  match.config.players = 2;
  match.config.start_players = 1;
  match.join(1, 5001);
  const auto late = match.join(2, 5002, MatchPhase::kRunning);
  ASSERT_EQ(late.kind, Kind::kSeated);
  EXPECT_EQ(late.seat, 1u);
  EXPECT_FALSE(late.rejoin);
}

TEST(MatchAdmission, ASecureSlotIsTheTokensAndNeverTakenFromAPresentHolder) {
  MatchConfig config;
  config.players = 2;
  config.max_spectators = 1;
  config.secure = true;
  MatchSeats seats(config.players, config.max_spectators);
  MatchAdmission admission(config, seats);
  const Admission alice{1, 100};
  const Admission mallory{1, 666};
  const auto seated =
      admission.admit(join_request(1), client_address(5001), MatchPhase::kLobby, alice, time_at(0));
  ASSERT_EQ(seated.kind, Kind::kSeated);
  EXPECT_EQ(seated.seat, 1u);
  EXPECT_EQ(seats[1].client_id, 100u);
  const auto stolen = admission.admit(join_request(2), client_address(5002), MatchPhase::kRunning,
                                      mallory, time_at(1));
  EXPECT_EQ(stolen.kind, Kind::kRejected);
  EXPECT_EQ(stolen.reason, "player slot 1 is held by another client");
  // Alice restarted: a new address, a fresh token for her client id.
  const auto back = admission.admit(join_request(3), client_address(5003), MatchPhase::kRunning,
                                    alice, time_at(2));
  EXPECT_EQ(back.kind, Kind::kSeated);
  EXPECT_TRUE(back.rejoin);
  EXPECT_EQ(seats[1].endpoint, client_address(5003));
  // A token naming a seat past the players is a spectator's.
  const auto watcher = admission.admit(join_request(4), client_address(5004), MatchPhase::kRunning,
                                       Admission{2, 7}, time_at(3));
  EXPECT_EQ(watcher.kind, Kind::kSeated);
  EXPECT_EQ(watcher.seat, 2u);
}

TEST(MatchAdmission, SilentOrDepartedLobbySeatsAreFreedAndNamed) {
  Tokenless match;
  match.join(1, 5001, MatchPhase::kLobby, false, 0.0);
  match.join(2, 5002, MatchPhase::kLobby, false, 4.0);
  match.join(3, 6001, MatchPhase::kLobby, true, 4.0);
  match.seats[2].left = true;
  // At 6 s the first player has been silent past the 5 s peer timeout.
  const std::vector<uint32_t> freed = match.admission.free_silent_lobby_seats(time_at(6.0));
  EXPECT_EQ(freed, (std::vector<uint32_t>{0, 2}));
  EXPECT_FALSE(match.seats[0].joined);
  EXPECT_TRUE(match.seats[1].joined);
  EXPECT_FALSE(match.seats[2].joined);
  EXPECT_EQ(match.join(4, 5004, MatchPhase::kLobby, false, 6.0).seat, 0u);
}

}  // namespace
}  // namespace rwd::server
