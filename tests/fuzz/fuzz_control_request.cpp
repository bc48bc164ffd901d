// SPDX-License-Identifier: MIT
// The control API, fed raw bytes: the endpoint's HTTP request parser, then
// ControlApi::handle against a stand-in server holding two matches (one
// per caller), and parse_match_request on the bytes as a query. Nothing
// may crash, and the API's rules must hold whatever arrives: no 2xx without
// a known bearer key, no match ended by a caller that neither allocated it
// nor is an admin, no match allocated past the quotas or under an id that
// is a path.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzz_entries.h"
#include "rewind/server/control_api.h"
#include "rewind/server/http_endpoint.h"
#include "rewind/server/match_request.h"

namespace {

using namespace rwd::server;

[[noreturn]] void invariant_broken(const char* what) {
  std::fprintf(stderr, "fuzz_control_request: invariant broken: %s\n", what);
  std::abort();
}

constexpr std::string_view kKeys =
    "alice 0123456789abcdef0123456789abcdef\n"
    "bob   fedcba9876543210fedcba9876543210\n"
    "root  00000000000000000000000000000000ffff admin\n";

class StandIn final : public ControlTarget {
 public:
  StandIn() {
    for (const char* owner : {"alice", "bob"}) {
      MatchListing m;
      m.id = std::string(owner) + "-match";
      m.owner = owner;
      m.game = "crates";
      matches.push_back(m);
    }
  }
  const MatchConfig& match_defaults() const override { return defaults; }
  rwd::Result<MatchListing> allocate_match(const MatchRequest& request,
                                           const std::string& owner) override {
    if (!is_match_id(request.match.match_id)) invariant_broken("allocated an id that is a path");
    if (!request.match.validate().ok()) invariant_broken("allocated an invalid config");
    MatchListing m;
    m.id = request.match.match_id;
    m.owner = owner;
    matches.push_back(m);
    ++allocated;
    return m;
  }
  std::vector<MatchListing> list_matches() const override { return matches; }
  rwd::Status stop_match(std::string_view id, const std::string& reason) override {
    stopped_id = std::string(id);
    stop_reason = reason;
    return rwd::Status::Ok();
  }
  bool stopping() const override { return false; }

  MatchConfig defaults;
  std::vector<MatchListing> matches;
  int allocated = 0;
  std::string stopped_id, stop_reason;
};

void check_query(std::string_view query) {
  const MatchConfig defaults;
  auto request = parse_match_request(query, defaults);
  if (!request.ok()) {
    if (request.status().message().empty()) invariant_broken("an error without a message");
    return;
  }
  if (!request->match.validate().ok()) invariant_broken("accepted an invalid config");
  if (query.size() > 1024) invariant_broken("accepted an oversized query");
}

}  // namespace

int fuzz_control_request_one(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  check_query(bytes);
  auto request = parse_http_request(bytes);
  if (!request.ok()) {
    if (request.status().message().empty()) invariant_broken("an error without a message");
    return 0;
  }
  if (request->target.empty() || request->target.front() != '/') {
    invariant_broken("parsed a target that is not a path");
  }
  static const ApiKeys keys = [] {
    auto parsed = ApiKeys::parse(kKeys);
    if (!parsed.ok()) invariant_broken("the stand-in keys do not parse");
    return *parsed;
  }();
  StandIn server;
  ControlPolicy policy;
  policy.lobbies_per_caller = 2;
  ControlApi api(server, keys, policy);
  const HttpReply reply = api.handle(*request);
  if (reply.status < 200 || reply.status > 599) invariant_broken("a status out of range");
  const std::optional<ApiCaller> caller = keys.authenticate(request->authorization);
  if (reply.status < 300 && !caller) invariant_broken("answered without a bearer key");
  if (!server.stopped_id.empty()) {
    if (!caller) invariant_broken("stopped a match without a bearer key");
    const std::string owner = server.stopped_id.substr(0, server.stopped_id.find('-'));
    if (!caller->admin && owner != caller->name) invariant_broken("stopped another's match");
  }
  if (server.allocated > 0) {
    if (!caller) invariant_broken("allocated without a bearer key");
    if (request->method != "POST") invariant_broken("allocated on a method but POST");
  }
  return 0;
}
