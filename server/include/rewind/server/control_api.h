// SPDX-License-Identifier: MIT
#pragma once
// The control API a match backend calls to allocate and end matches:
//
//   GET    /matches            every match (running, and the newest ended)
//   GET    /matches/<id>       one match
//   POST   /matches?id=..&..   allocate one (MatchRequest's keys): 201
//   DELETE /matches/<id>       end a running match: 202
//
// Every call needs `Authorization: Bearer <key>` naming a caller of the
// key file (ApiKeys): 401 without it. The rules a shared server needs:
// a caller has at most ControlPolicy::lobbies_per_caller matches waiting
// for players, none waiting longer than max_lobby_seconds; an id is a name
// (never a path) and is not reused while its replay file exists (409);
// only the caller that allocated a match, or an admin, may end it (403).
// No socket here: the server's HTTP endpoint hands requests in, and the
// matches are reached through ControlTarget, so the rules are testable
// and fuzzable on their own.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/server/api_keys.h"
#include "rewind/server/http_endpoint.h"
#include "rewind/server/match_host.h"
#include "rewind/server/match_request.h"

namespace rwd::server {

struct ControlPolicy {
  /// Matches one caller may have in their lobby at once, [1, 256].
  uint32_t lobbies_per_caller = 4;
  /// The longest join timeout a call may ask for, seconds, [1, 86400].
  double max_lobby_seconds = 600;

  Status validate() const;
};

/// One match as the control API lists it.
struct MatchListing {
  std::string id;
  std::string owner;  ///< the caller that allocated it; empty for launch matches
  std::string game;
  uint16_t port = 0;
  uint32_t players = 0;
  MatchHost::Phase phase = MatchHost::Phase::kLobby;
  uint32_t players_connected = 0;
  int64_t ticks_final = 0;
  std::string end_reason;
  bool ended = false;
};

/// What the control API acts on: the server, or a test's stand-in.
class ControlTarget {
 public:
  virtual ~ControlTarget() = default;
  /// The settings a request starts from.
  virtual const MatchConfig& match_defaults() const = 0;
  /// Starts a match for `owner`. kInvalidArgument: the id is alive or its
  /// replay exists; kCapacity: the server is full; kIo: bind failed.
  virtual Result<MatchListing> allocate_match(const MatchRequest& request,
                                              const std::string& owner) = 0;
  /// Running matches first in creation order, then the ended ones kept.
  virtual std::vector<MatchListing> list_matches() const = 0;
  /// Ends the running match `id`; kNotFound when none runs.
  virtual Status stop_match(std::string_view id, const std::string& reason) = 0;
  /// True once the server is ending every match.
  virtual bool stopping() const = 0;
};

class ControlApi {
 public:
  ControlApi(ControlTarget& target, ApiKeys keys, ControlPolicy policy);
  /// Answers one request (any method and target; 404 off the API).
  HttpReply handle(const HttpRequest& request);

 private:
  HttpReply allocate(const ApiCaller& caller, std::string_view query);
  HttpReply stop(const ApiCaller& caller, std::string_view id);

  ControlTarget& target_;
  ApiKeys keys_;
  ControlPolicy policy_;
};

/// A listing as the API's JSON object.
std::string listing_json(const MatchListing& listing);

}  // namespace rwd::server
