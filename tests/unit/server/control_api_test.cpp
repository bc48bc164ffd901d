// SPDX-License-Identifier: MIT
// The control API's rules against a stand-in server: bearer keys, quotas
// per caller, the longest lobby, ids that are names, and who may end a
// match.
#include "rewind/server/control_api.h"

#include <gtest/gtest.h>

namespace rwd::server {
namespace {

constexpr std::string_view kAlice = "Bearer aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa";
constexpr std::string_view kBob = "Bearer bbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbb";
constexpr std::string_view kRoot = "Bearer rrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrr";

MatchListing listing(std::string id, std::string owner) {
  MatchListing m;
  m.id = std::move(id);
  m.owner = std::move(owner);
  return m;
}

class StandIn final : public ControlTarget {
 public:
  const MatchConfig& match_defaults() const override { return defaults; }
  Result<MatchListing> allocate_match(const MatchRequest& request,
                                      const std::string& owner) override {
    if (!refusal.ok()) return refusal;
    MatchListing m;
    m.id = request.match.match_id;
    m.owner = owner;
    m.port = static_cast<uint16_t>(9000 + matches.size());
    matches.push_back(m);
    return m;
  }
  std::vector<MatchListing> list_matches() const override { return matches; }
  Status stop_match(std::string_view id, const std::string& reason) override {
    for (MatchListing& m : matches) {
      if (m.id == id) {
        m.ended = true;
        m.end_reason = reason;
      }
    }
    return Status::Ok();
  }
  bool stopping() const override { return false; }

  MatchConfig defaults;
  std::vector<MatchListing> matches;
  Status refusal = Status::Ok();
};

class ControlApiTest : public ::testing::Test {
 protected:
  ControlApiTest() : api_(server_, keys(), policy()) {}

  static ApiKeys keys() {
    auto parsed = ApiKeys::parse(
        "alice aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa\n"
        "bob   bbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbbb\n"
        "root  rrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrrr admin\n");
    EXPECT_TRUE(parsed.ok()) << parsed.status().message();
    return *parsed;
  }
  static ControlPolicy policy() {
    ControlPolicy p;
    p.lobbies_per_caller = 2;
    p.max_lobby_seconds = 120;
    return p;
  }

  HttpReply call(std::string method, std::string target, std::string_view key) {
    HttpRequest request;
    request.method = std::move(method);
    request.target = std::move(target);
    request.authorization = std::string(key);
    return api_.handle(request);
  }

  StandIn server_;
  ControlApi api_;
};

TEST_F(ControlApiTest, EveryCallNeedsAKnownBearerKey) {
  server_.matches.push_back(listing("m", "alice"));
  for (const std::string_view key :
       {std::string_view(), std::string_view("Bearer wrong-wrong-wrong-wrong-wrong-wrong"),
        std::string_view("Basic YWxpY2U6YQ==")}) {
    const HttpReply list = call("GET", "/matches", key);
    EXPECT_EQ(list.status, 401u);
    EXPECT_EQ(list.body.find("\"m\""), std::string::npos) << "leaked the list";
    EXPECT_EQ(call("POST", "/matches?id=x", key).status, 401u);
    EXPECT_EQ(call("DELETE", "/matches/m", key).status, 401u);
    EXPECT_EQ(call("GET", "/matches/m", key).status, 401u);
  }
  EXPECT_EQ(server_.matches.size(), 1u);
  EXPECT_FALSE(server_.matches[0].ended);
  const HttpReply list = call("GET", "/matches", kBob);
  EXPECT_EQ(list.status, 200u);
  EXPECT_NE(list.body.find("\"owner\":\"alice\""), std::string::npos) << list.body;
  EXPECT_EQ(call("GET", "/metrics", kBob).status, 404u);
}

TEST_F(ControlApiTest, AllocatesForItsCallerWithinTheQuotas) {
  const HttpReply made = call("POST", "/matches?id=duel-1&players=2", kAlice);
  EXPECT_EQ(made.status, 201u) << made.body;
  EXPECT_NE(made.body.find("\"id\":\"duel-1\""), std::string::npos);
  ASSERT_EQ(server_.matches.size(), 1u);
  EXPECT_EQ(server_.matches[0].owner, "alice");
  EXPECT_EQ(call("POST", "/matches?id=duel-2", kAlice).status, 201u);
  // Two lobbies waiting is alice's most; bob's quota is his own.
  const HttpReply third = call("POST", "/matches?id=duel-3", kAlice);
  EXPECT_EQ(third.status, 429u) << third.body;
  EXPECT_EQ(call("POST", "/matches?id=bobs", kBob).status, 201u);
  // Once a lobby fills, it no longer counts.
  server_.matches[0].phase = MatchHost::Phase::kRunning;
  EXPECT_EQ(call("POST", "/matches?id=duel-3", kAlice).status, 201u);
}

TEST_F(ControlApiTest, LongLobbiesAndPathIdsAreRefused) {
  const HttpReply day = call("POST", "/matches?id=slow&join_timeout=86400", kAlice);
  EXPECT_EQ(day.status, 400u);
  EXPECT_NE(day.body.find("longest lobby"), std::string::npos) << day.body;
  EXPECT_EQ(call("POST", "/matches?id=ok&join_timeout=120", kAlice).status, 201u);
  for (const char* id : {"..", ".", ".hidden", "a..b", "a/b", "a%2fb"}) {
    EXPECT_EQ(call("POST", std::string("/matches?id=") + id, kAlice).status, 400u) << id;
  }
  EXPECT_EQ(call("DELETE", "/matches/..", kRoot).status, 404u);
  EXPECT_EQ(server_.matches.size(), 1u);
}

TEST_F(ControlApiTest, OnlyTheOwnerOrAnAdminEndsAMatch) {
  ASSERT_EQ(call("POST", "/matches?id=alices", kAlice).status, 201u);
  const HttpReply bobs_try = call("DELETE", "/matches/alices", kBob);
  EXPECT_EQ(bobs_try.status, 403u) << bobs_try.body;
  EXPECT_FALSE(server_.matches[0].ended);
  EXPECT_EQ(call("DELETE", "/matches/alices", kAlice).status, 202u);
  EXPECT_TRUE(server_.matches[0].ended);
  EXPECT_EQ(call("DELETE", "/matches/alices", kAlice).status, 404u);  // already ended
  // Launch matches belong to nobody: an admin only.
  server_.matches.push_back(listing("launch", ""));
  EXPECT_EQ(call("DELETE", "/matches/launch", kAlice).status, 403u);
  EXPECT_EQ(call("DELETE", "/matches/launch", kRoot).status, 202u);
  EXPECT_NE(server_.matches[1].end_reason.find("root"), std::string::npos);
}

TEST_F(ControlApiTest, TheServersRefusalsKeepTheirMeaning) {
  server_.refusal = Status::Error(ErrorCode::kInvalidArgument, "match id 'x' has a replay");
  const HttpReply taken = call("POST", "/matches?id=x", kAlice);
  EXPECT_EQ(taken.status, 409u);
  EXPECT_NE(taken.body.find("has a replay"), std::string::npos);
  server_.refusal = Status::Error(ErrorCode::kCapacity, "full");
  EXPECT_EQ(call("POST", "/matches?id=x", kAlice).status, 503u);
  EXPECT_EQ(call("PUT", "/matches", kAlice).status, 405u);
  EXPECT_EQ(call("POST", "/matches/x", kAlice).status, 405u);
}

TEST(ControlPolicy, RefusesSettingsOutOfRange) {
  ControlPolicy policy;
  EXPECT_TRUE(policy.validate().ok());
  policy.lobbies_per_caller = 0;
  EXPECT_FALSE(policy.validate().ok());
  policy = {};
  policy.max_lobby_seconds = 0.5;
  EXPECT_FALSE(policy.validate().ok());
}

}  // namespace
}  // namespace rwd::server
