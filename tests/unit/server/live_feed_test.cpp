// SPDX-License-Identifier: MIT
// Spectating in a browser: a match host publishes to its LiveFeed, and a
// viewer that starts from the feed at any point (a view bundle from the
// newest state) and polls its ticks re-simulates every final tick with the
// server's checksum. The feed stays bounded, holds spectators back by its
// delay, and the live endpoint's routes answer as documented.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "http_test_client.h"
#include "match_host_harness.h"
#include "rewind/server/live_api.h"
#include "rewind/server/server.h"
#include "rewind/viewer/live_ticks.h"
#include "rewind/viewer/replay_player.h"
#include "scratch_dir.h"

namespace rwd::server {
namespace {

using host_test::HostHarness;

std::vector<uint8_t> start_of(const LiveFeed& feed) {
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(feed.start_bundle(bytes).ok());
  return bytes;
}

/// A viewer as the browser runs it: start from the feed now, then poll.
std::unique_ptr<viewer::ReplayPlayer> viewer_of(const LiveFeed& feed) {
  auto bundle = viewer::decode_view_bundle(start_of(feed));
  EXPECT_TRUE(bundle.ok()) << bundle.status().message();
  auto player = viewer::ReplayPlayer::create(std::move(*bundle), 30, 4);
  EXPECT_TRUE(player.ok()) << player.status().message();
  return std::move(*player);
}

void poll(const LiveFeed& feed, viewer::ReplayPlayer& player) {
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(feed.ticks_from(player.length(), bytes).ok());
  auto batch = viewer::decode_live_ticks(bytes);
  ASSERT_TRUE(batch.ok()) << batch.status().message();
  ASSERT_TRUE(player.append(*batch).ok());
}

TEST(LiveFeed, ViewersJoiningAtAnyTickReSimulateTheServersChecksums) {
  MatchConfig config = host_test::test_config();
  HostHarness h(config);
  LiveFeed::Info info;
  info.match_id = "m";
  info.game = "crates";
  info.setup = h.host().session().simulation().setup();
  info.keyframe_ticks = 40;
  auto feed = std::make_shared<LiveFeed>(info);
  h.host().attach_live_feed(feed);

  std::vector<std::unique_ptr<viewer::ReplayPlayer>> viewers;
  const auto finals = host_test::play(
      h, 260, [&](HostHarness&, host_test::FakeClient&, host_test::FakeClient&, Tick t) {
        if (t == 0 || t == 45 || t == 130) viewers.push_back(viewer_of(*feed));
        if (t % 7 == 0) {
          for (auto& v : viewers) poll(*feed, *v);
        }
      });
  ASSERT_EQ(viewers.size(), 3u);
  EXPECT_EQ(viewers[0]->start(), 0);
  EXPECT_EQ(viewers[1]->start(), 40);  // the newest state published
  EXPECT_EQ(viewers[2]->start(), 120);
  const Tick last = h.host().last_final_tick();
  ASSERT_GT(last, 240);
  for (auto& v : viewers) {
    poll(*feed, *v);
    EXPECT_EQ(v->length(), last + 1);
    while (v->step()) {
    }
    EXPECT_FALSE(v->first_mismatch().has_value()) << "from " << v->start();
    EXPECT_EQ(v->checksum(), finals.at(last));
  }
  // Late joiners start from the newest state, not from tick 0.
  EXPECT_EQ(viewer_of(*feed)->start(), (last + 1) / 40 * 40);
}

LiveFeed::Info plain_info(uint32_t keyframe_ticks, uint32_t delay_ticks) {
  LiveFeed::Info info;
  info.match_id = "duel";
  info.game = "arena";
  info.setup = {2, 9};
  info.keyframe_ticks = keyframe_ticks;
  info.delay_ticks = delay_ticks;
  return info;
}

/// Ticks 0..count-1 with made-up checksums and a stand-in state every
/// keyframe (the feed does not look inside states).
void publish(LiveFeed& feed, Tick from, Tick count) {
  const std::vector<rwd::PlayerInput> inputs(2);
  for (Tick t = from; t < from + count; ++t) {
    feed.publish_tick(t, inputs, 0, 1000 + static_cast<uint64_t>(t));
    if (feed.wants_state(t + 1)) feed.publish_state(t + 1, std::vector<uint8_t>{1, 2, 3});
  }
}

viewer::LiveTicks ticks_of(const LiveFeed& feed, Tick from) {
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(feed.ticks_from(from, bytes).ok());
  return *viewer::decode_live_ticks(bytes);
}

TEST(LiveFeed, HoldsAFewStatesAndTheTicksSinceTheOldest) {
  LiveFeed feed(plain_info(10, 0));
  publish(feed, 0, 1000);
  std::vector<uint8_t> bytes;
  // Three states (980, 990, 1000): ticks from 980 on.
  EXPECT_EQ(feed.ticks_from(979, bytes).code(), ErrorCode::kNotFound);
  EXPECT_EQ(feed.ticks_from(0, bytes).code(), ErrorCode::kNotFound);
  EXPECT_EQ(feed.ticks_from(-1, bytes).code(), ErrorCode::kInvalidArgument);
  const viewer::LiveTicks held = ticks_of(feed, 980);
  EXPECT_EQ(held.tick_count(), 20u);
  EXPECT_EQ(held.checksums.front(), 1980u);
  EXPECT_EQ(held.newest_final, 999);
  EXPECT_EQ(ticks_of(feed, 1000).tick_count(), 0u);  // nothing new yet
  EXPECT_EQ(ticks_of(feed, 5000).tick_count(), 0u);
  auto start = viewer::decode_view_bundle(start_of(feed));
  ASSERT_TRUE(start.ok());
  EXPECT_EQ(start->first_tick, 1000);
  EXPECT_EQ(start->tick_count(), 0u);
  EXPECT_EQ(start->start_state, (std::vector<uint8_t>{1, 2, 3}));

  // Out of order or after the end: ignored.
  const std::vector<rwd::PlayerInput> inputs(2);
  feed.publish_tick(1005, inputs, 0, 1);
  feed.publish_tick(998, inputs, 0, 1);
  feed.publish_tick(1000, std::vector<rwd::PlayerInput>(3), 0, 1);  // three inputs for two
  EXPECT_EQ(feed.summary().newest_final, 999);
  feed.end();
  feed.publish_tick(1000, inputs, 0, 1);
  EXPECT_EQ(feed.summary().newest_final, 999);
  EXPECT_TRUE(ticks_of(feed, 990).ended);
}

TEST(LiveFeed, SpectatorsTrailByTheDelayUntilTheEnd) {
  LiveFeed feed(plain_info(20, 30));
  publish(feed, 0, 100);
  const viewer::LiveTicks seen = ticks_of(feed, 60);
  EXPECT_EQ(seen.newest_final, 99);
  ASSERT_EQ(seen.tick_count(), 10u);  // 60..69: 70 and later are 30 ticks fresh
  // The start is the newest state a spectator may see: 60, not 100.
  auto start = viewer::decode_view_bundle(start_of(feed));
  ASSERT_TRUE(start.ok());
  EXPECT_EQ(start->first_tick, 60);
  EXPECT_EQ(start->tick_count(), 10u);
  // A delay keeps what the spectators have not seen yet.
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(feed.ticks_from(40, bytes).ok());
  EXPECT_EQ(feed.summary().published, 69);
  feed.end();  // the match is over: nothing left to hide
  EXPECT_EQ(ticks_of(feed, 60).tick_count(), 40u);
  EXPECT_EQ(feed.summary().published, 99);
}

TEST(LiveFeed, NamesFollowTheSeats) {
  LiveFeed feed(plain_info(10, 0));
  EXPECT_EQ(feed.summary().player_names, (std::vector<std::string>{"", ""}));
  feed.publish_names({"ann", "bo"});
  feed.publish_names({"only one"});  // not one per player: ignored
  publish(feed, 0, 3);
  EXPECT_EQ(ticks_of(feed, 0).player_names, (std::vector<std::string>{"ann", "bo"}));
  feed.publish_names({std::string(1000, 'x'), "bo"});
  EXPECT_EQ(feed.summary().player_names[0].size(), viewer::kViewMaxString);
}

TEST(LiveFeed, TheHostPublishesNamesAndTheEnd) {
  HostHarness h(host_test::test_config());
  auto feed = std::make_shared<LiveFeed>(plain_info(10, 0));
  h.host().attach_live_feed(feed);
  host_test::play(h, 20, nullptr);
  EXPECT_GE(feed->summary().newest_final, 10);
  EXPECT_FALSE(feed->summary().ended);
  h.host().end("test over", net::SteadyClock::now());
  EXPECT_TRUE(feed->summary().ended);
}

/// Stand-in viewer files in `dir`.
std::string fake_viewer_in(const test::ScratchDir& dir) {
  for (const char* name : kViewerFiles) std::ofstream(dir.path() / name) << "file " << name;
  return dir.path().string();
}

HttpRequest get(std::string target) {
  HttpRequest request;
  request.method = "GET";
  request.target = std::move(target);
  return request;
}

TEST(LiveApi, AnswersEveryRouteAsDocumented) {
  auto feed = std::make_shared<LiveFeed>(plain_info(10, 0));
  feed->publish_names({"<ann>", "bo"});
  publish(*feed, 0, 50);
  const test::ScratchDir dir("live_api_viewer");
  auto viewer = StaticFiles::load_viewer(fake_viewer_in(dir));
  ASSERT_TRUE(viewer.ok()) << viewer.status().message();
  const LiveApi api(
      [feed](std::string_view id) {
        return id == "duel" ? std::shared_ptr<const LiveFeed>(feed) : nullptr;
      },
      [feed] { return std::vector<std::shared_ptr<const LiveFeed>>{feed}; }, std::move(*viewer));

  const HttpReply listing = api.handle(get("/"));
  EXPECT_EQ(listing.status, 200u);
  EXPECT_NE(listing.body.find("href=\"/?live=duel\""), std::string::npos);
  EXPECT_NE(listing.body.find("&lt;ann&gt;"), std::string::npos);  // escaped
  EXPECT_EQ(api.handle(get("/?live=duel")).body, "file index.html");
  EXPECT_EQ(api.handle(get("/viewer.js")).body, "file viewer.js");

  const HttpReply json = api.handle(get("/live/matches"));
  EXPECT_EQ(json.status, 200u);
  const auto list = nlohmann::json::parse(json.body);
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0]["match"], "duel");
  EXPECT_EQ(list[0]["final_tick"], 49);
  EXPECT_EQ(list[0]["names"][0], "<ann>");

  const HttpReply start = api.handle(get("/live/duel/start"));
  EXPECT_EQ(start.status, 200u);
  EXPECT_TRUE(
      viewer::decode_view_bundle(std::vector<uint8_t>(start.body.begin(), start.body.end())).ok());
  const HttpReply ticks = api.handle(get("/live/duel/ticks?from=45"));
  EXPECT_EQ(ticks.status, 200u);
  auto batch =
      viewer::decode_live_ticks(std::vector<uint8_t>(ticks.body.begin(), ticks.body.end()));
  ASSERT_TRUE(batch.ok());
  EXPECT_EQ(batch->tick_count(), 5u);

  EXPECT_EQ(api.handle(get("/live/duel/ticks?from=0")).status, 410u);  // dropped
  EXPECT_EQ(api.handle(get("/live/duel/ticks")).status, 400u);
  EXPECT_EQ(api.handle(get("/live/duel/ticks?from=")).status, 400u);
  EXPECT_EQ(api.handle(get("/live/duel/ticks?from=12x")).status, 400u);
  EXPECT_EQ(api.handle(get("/live/duel/ticks?from=-3")).status, 400u);
  EXPECT_EQ(api.handle(get("/live/other/start")).status, 404u);
  EXPECT_EQ(api.handle(get("/live/duel/state")).status, 404u);
  EXPECT_EQ(api.handle(get("/live/duel")).status, 404u);
  EXPECT_EQ(api.handle(get("/nothing.js")).status, 404u);
  HttpRequest post = get("/live/duel/start");
  post.method = "POST";
  EXPECT_EQ(api.handle(post).status, 405u);
}

TEST(LiveApi, WithoutViewerFilesServesTheDataAndSaysSo) {
  const LiveApi api([](std::string_view) { return nullptr; },
                    [] { return std::vector<std::shared_ptr<const LiveFeed>>{}; }, std::nullopt);
  const HttpReply listing = api.handle(get("/?live=x"));
  EXPECT_EQ(listing.status, 200u);
  EXPECT_NE(listing.body.find("no viewer files"), std::string::npos);
  EXPECT_NE(listing.body.find("No match is live"), std::string::npos);
  EXPECT_EQ(api.handle(get("/viewer.js")).status, 404u);
}

TEST(LiveServer, ServesItsMatchesOnTheLiveEndpoint) {
  ServerConfig config;
  config.bind_address = "127.0.0.1";
  config.port = 0;
  config.live = ServerConfig::HttpBind{"127.0.0.1", 0};
  const test::ScratchDir dir("live_server_viewer");
  config.live_viewer_dir = fake_viewer_in(dir);
  auto server = Server::create(config);
  ASSERT_TRUE(server.ok()) << server.status().message();
  ASSERT_NE((*server)->live_port(), 0);
  testing_http::Client client((*server)->live_port());
  const std::string response =
      client.exchange("GET /live/matches HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  ASSERT_EQ(testing_http::status_of(response), 200) << response;
  const auto list = nlohmann::json::parse(testing_http::body_of(response));
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0]["match"], "match");
  EXPECT_EQ(list[0]["final_tick"], -1);  // still in the lobby
  const std::string page =
      client.exchange("GET /?live=match HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(testing_http::body_of(page), "file index.html");

  config.live_viewer_dir = (dir.path() / "no_such_viewer").string();
  auto refused = Server::create(config);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("viewer is not built"), std::string::npos);
}

}  // namespace
}  // namespace rwd::server
