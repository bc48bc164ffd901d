// SPDX-License-Identifier: MIT
#include "rewind/server/control_api.h"

#include <nlohmann/json.hpp>

namespace rwd::server {
namespace {

using Json = nlohmann::json;

HttpReply json_reply(unsigned status, const Json& body) {
  HttpReply reply;
  reply.status = status;
  // Messages may quote what the caller sent: bytes that are not UTF-8
  // become U+FFFD rather than an exception.
  reply.body = body.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
  return reply;
}

HttpReply error_reply(unsigned status, std::string_view message) {
  return json_reply(status, Json{{"error", message}});
}

Json listing_object(const MatchListing& m) {
  return Json{{"id", m.id},
              {"owner", m.owner},
              {"port", m.port},
              {"game", m.game},
              {"players", m.players},
              {"phase", phase_name(m.phase)},
              {"players_connected", m.players_connected},
              {"ticks_final", m.ticks_final},
              {"end_reason", m.end_reason}};
}

}  // namespace

Status ControlPolicy::validate() const {
  if (lobbies_per_caller < 1 || lobbies_per_caller > 256) {
    return Status::Error(ErrorCode::kInvalidArgument, "lobbies per caller must be in [1, 256]");
  }
  if (!(max_lobby_seconds >= 1 && max_lobby_seconds <= 86400)) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "the longest lobby must be in [1, 86400] seconds");
  }
  return Status::Ok();
}

std::string listing_json(const MatchListing& listing) {
  return listing_object(listing).dump(-1, ' ', false, Json::error_handler_t::replace);
}

ControlApi::ControlApi(ControlTarget& target, ApiKeys keys, ControlPolicy policy)
    : target_(target), keys_(std::move(keys)), policy_(policy) {}

HttpReply ControlApi::handle(const HttpRequest& request) {
  const std::string_view path = request.path();
  constexpr std::string_view kMatches = "/matches";
  if (path != kMatches && !path.starts_with("/matches/")) {
    return error_reply(404, "not found: the control API is /matches");
  }
  // Who asks comes before what is asked: an unauthenticated caller learns
  // nothing, not even whether a match exists.
  const std::optional<ApiCaller> caller = keys_.authenticate(request.authorization);
  if (!caller) {
    HttpReply reply = error_reply(401, "a bearer key is required (Authorization: Bearer <key>)");
    reply.headers.emplace_back("WWW-Authenticate", "Bearer realm=\"rewind-control\"");
    return reply;
  }
  const std::string_view method = request.method;
  if (path == kMatches) {
    if (method == "GET" || method == "HEAD") {
      Json all = Json::array();
      for (const MatchListing& listing : target_.list_matches())
        all.push_back(listing_object(listing));
      return json_reply(200, all);
    }
    if (method == "POST") return allocate(*caller, request.query());
    return error_reply(405, "GET or POST /matches");
  }
  const std::string_view id = path.substr(kMatches.size() + 1);
  if (!is_match_id(id)) return error_reply(404, "no match with that id");
  if (method == "GET" || method == "HEAD") {
    for (const MatchListing& listing : target_.list_matches()) {
      if (listing.id == id) return json_reply(200, listing_object(listing));
    }
    return error_reply(404, "no match with that id");
  }
  if (method == "DELETE") return stop(*caller, id);
  return error_reply(405, "GET or DELETE /matches/<id>");
}

HttpReply ControlApi::allocate(const ApiCaller& caller, std::string_view query) {
  if (target_.stopping()) return error_reply(503, "the server is stopping");
  auto request = parse_match_request(query, target_.match_defaults());
  if (!request.ok()) return error_reply(400, request.status().message());
  if (request->match.join_timeout_s > policy_.max_lobby_seconds) {
    return error_reply(400, "'join_timeout' is above this server's longest lobby (" +
                                std::to_string(static_cast<int64_t>(policy_.max_lobby_seconds)) +
                                " s)");
  }
  uint32_t waiting = 0;
  for (const MatchListing& listing : target_.list_matches()) {
    waiting +=
        !listing.ended && listing.phase == MatchHost::Phase::kLobby && listing.owner == caller.name;
  }
  if (waiting >= policy_.lobbies_per_caller) {
    return error_reply(429, "'" + caller.name + "' already has " + std::to_string(waiting) +
                                " matches waiting for players (the most per caller)");
  }
  auto listing = target_.allocate_match(*request, caller.name);
  if (!listing.ok()) {
    const ErrorCode code = listing.status().code();
    return error_reply(code == ErrorCode::kCapacity          ? 503
                       : code == ErrorCode::kInvalidArgument ? 409
                                                             : 500,
                       listing.status().message());
  }
  return json_reply(201, Json{{"id", listing->id}, {"port", listing->port}});
}

HttpReply ControlApi::stop(const ApiCaller& caller, std::string_view id) {
  for (const MatchListing& listing : target_.list_matches()) {
    if (listing.id != id || listing.ended) continue;
    if (!caller.admin && listing.owner != caller.name) {
      return error_reply(403, "only the caller that allocated a match, or an admin, may end it");
    }
    if (Status status = target_.stop_match(id, "stopped by the control API (" + caller.name + ")");
        !status.ok()) {
      return error_reply(404, status.message());
    }
    return json_reply(202, Json{{"id", listing.id}, {"stopping", true}});
  }
  return error_reply(404, "no running match with that id");
}

}  // namespace rwd::server
