// SPDX-License-Identifier: MIT
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzz_entries.h"
#include "rewind/server/http_response.h"

namespace {

[[noreturn]] void invariant_broken(const char* what) {
  std::fprintf(stderr, "fuzz_http_response: invariant broken: %s\n", what);
  std::abort();
}

}  // namespace

int fuzz_http_response_one(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  constexpr size_t kMaxBody = 512;
  auto response = rwd::server::parse_http_response(bytes, kMaxBody);
  if (!response.ok()) {
    const rwd::ErrorCode code = response.status().code();
    if (code != rwd::ErrorCode::kCorrupt && code != rwd::ErrorCode::kCapacity) {
      invariant_broken("error neither kCorrupt nor kCapacity");
    }
    if (response.status().message().empty()) invariant_broken("error without message");
    return 0;
  }
  if (response->status < 100 || response->status > 599) invariant_broken("status out of range");
  if (response->body.size() > kMaxBody) invariant_broken("body over the limit");
  if (response->body.size() > size) invariant_broken("body longer than the input");
  // The body, re-framed by Content-Length, must read back the same.
  const std::string again =
      "HTTP/1.1 " + std::to_string(response->status) + " " + response->reason +
      "\r\nContent-Length: " + std::to_string(response->body.size()) + "\r\n\r\n" + response->body;
  const bool bodiless =
      response->status < 200 || response->status == 204 || response->status == 304;
  auto round = rwd::server::parse_http_response(again, kMaxBody);
  if (bodiless) {
    if (!response->body.empty()) invariant_broken("a bodiless status with a body");
    return 0;
  }
  if (!round.ok()) invariant_broken("re-framed response refused");
  if (round->body != response->body || round->reason != response->reason) {
    invariant_broken("re-framing changed the response");
  }
  return 0;
}
