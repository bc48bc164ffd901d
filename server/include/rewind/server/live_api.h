// SPDX-License-Identifier: MIT
#pragma once
// The server's live endpoint (ServerConfig::live): browsers spectate the
// matches it hosts, read-only, over plain HTTP polls that any browser can
// make. Every route is GET (or HEAD):
//
//   /                     a page listing the live matches, each a link to
//                         the viewer (with no viewer files: the list only)
//   /?live=<match>        the viewer (viewer_web's index.html) in live mode
//   /<viewer file>        the viewer's page and engine (StaticFiles)
//   /live/matches         the matches as JSON: [{"match","game","players",
//                         "names","final_tick","visible_tick","tick_rate",
//                         "ended"}]
//   /live/<match>/start   a view bundle to start from (LiveFeed::start_bundle)
//   /live/<match>/ticks?from=T
//                         a live tick batch from T (LiveFeed::ticks_from);
//                         410 when T is no longer held (start over)
//
// 404 names an unknown match or path, 400 a bad `from`, 405 another method.
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "rewind/server/http_endpoint.h"
#include "rewind/server/live_feed.h"
#include "rewind/server/static_files.h"

namespace rwd::server {

class LiveApi {
 public:
  /// The feed of match `id`; null when there is none (or it is not live).
  using FindFn = std::function<std::shared_ptr<const LiveFeed>(std::string_view id)>;
  /// Every live match's feed, in the order to list them.
  using ListFn = std::function<std::vector<std::shared_ptr<const LiveFeed>>()>;

  /// `viewer`: the viewer's files to serve; none: the data routes only.
  LiveApi(FindFn find, ListFn list, std::optional<StaticFiles> viewer);

  /// Answers one request; on the endpoint's thread.
  HttpReply handle(const HttpRequest& request) const;
  /// When the last request came (steady clock); the epoch before any. For
  /// a server that stays up while spectators still poll.
  std::chrono::steady_clock::time_point last_request() const {
    return std::chrono::steady_clock::time_point(
        std::chrono::steady_clock::duration(last_request_.load(std::memory_order_relaxed)));
  }

 private:
  HttpReply listing_page() const;
  HttpReply listing_json() const;
  HttpReply match_route(std::string_view rest, std::string_view query) const;

  FindFn find_;
  ListFn list_;
  std::optional<StaticFiles> viewer_;
  mutable std::atomic<std::chrono::steady_clock::rep> last_request_{0};
};

}  // namespace rwd::server
