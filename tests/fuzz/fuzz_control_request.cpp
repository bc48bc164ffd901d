// SPDX-License-Identifier: MIT
// The control API's parsers, fed one HTTP request head: MetricsHttp's
// request-line and header checks, then, for the routed targets,
// parse_match_request on the query. Neither may crash; an accepted match
// request must be a valid config and use only the query it was given.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzz_entries.h"
#include "rewind/server/match_request.h"
#include "rewind/server/metrics_http.h"

namespace {

[[noreturn]] void invariant_broken(const char* what) {
  std::fprintf(stderr, "fuzz_control_request: invariant broken: %s\n", what);
  std::abort();
}

void check_request(std::string_view query) {
  const rwd::server::MatchConfig defaults;
  auto request = rwd::server::parse_match_request(query, defaults);
  if (!request.ok()) {
    if (request.status().message().empty()) invariant_broken("an error without a message");
    return;
  }
  if (!request->match.validate().ok()) invariant_broken("accepted an invalid config");
  if (query.size() > 1024) invariant_broken("accepted an oversized query");
  if (request->match.match_id != defaults.match_id &&
      query.find("id=" + request->match.match_id) == std::string_view::npos) {
    invariant_broken("a match id not taken from the query");
  }
}

}  // namespace

int fuzz_control_request_one(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // As a query on its own, and as a whole request head.
  check_request(bytes);
  bool routed = false;
  const std::string answer = rwd::server::MetricsHttp::respond(
      bytes, [] { return std::string("rewind_matches 0\n"); },
      [&](std::string_view method, std::string_view target) {
        routed = true;
        if (method.empty() || target.empty() || target.front() != '/') {
          invariant_broken("routed a request line that does not parse");
        }
        const size_t question = target.find('?');
        if (question != std::string_view::npos) check_request(target.substr(question + 1));
        return std::optional<rwd::server::HttpAnswer>();
      });
  if (!answer.starts_with("HTTP/1.1 ")) invariant_broken("an answer that is not HTTP");
  if (routed && answer.starts_with("HTTP/1.1 400")) invariant_broken("routed a bad request");
  return 0;
}
