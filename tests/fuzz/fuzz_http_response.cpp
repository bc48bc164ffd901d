// SPDX-License-Identifier: MIT
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzz_entries.h"
#include "rewind/server/http_client.h"

namespace {

[[noreturn]] void invariant_broken(const char* what) {
  std::fprintf(stderr, "fuzz_http_response: invariant broken: %s\n", what);
  std::abort();
}

}  // namespace

int fuzz_http_response_one(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  rwd::server::HttpResponseLimits limits;
  limits.max_body_bytes = 512;  // small, so the fuzzer reaches the bounds
  limits.max_header_bytes = 1024;
  auto response = rwd::server::parse_http_response(bytes, limits);
  if (!response.ok()) {
    const rwd::ErrorCode code = response.status().code();
    if (code != rwd::ErrorCode::kCorrupt && code != rwd::ErrorCode::kCapacity) {
      invariant_broken("error neither kCorrupt nor kCapacity");
    }
    if (response.status().message().empty()) invariant_broken("error without message");
    return 0;
  }
  if (response->status < 100 || response->status > 599) invariant_broken("status out of range");
  if (response->body.size() > limits.max_body_bytes) invariant_broken("body over the limit");
  if (response->body.size() > size) invariant_broken("body longer than the input");
  const bool bodiless =
      response->status < 200 || response->status == 204 || response->status == 304;
  if (bodiless) {
    if (!response->body.empty()) invariant_broken("a bodiless status with a body");
    return 0;
  }
  // The body, re-framed by Content-Length, must read back the same.
  const std::string again =
      "HTTP/1.1 " + std::to_string(response->status) + " " + response->reason +
      "\r\nContent-Length: " + std::to_string(response->body.size()) + "\r\n\r\n" + response->body;
  auto round = rwd::server::parse_http_response(again, limits);
  if (!round.ok()) invariant_broken("re-framed response refused");
  if (round->status != response->status || round->body != response->body ||
      round->reason != response->reason) {
    invariant_broken("re-framing changed the response");
  }
  return 0;
}
