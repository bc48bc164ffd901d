// SPDX-License-Identifier: MIT
// Reading whole HTTP/1.1 responses: each body framing, and the malformed or
// ambiguous responses that must be refused.
#include "rewind/server/http_response.h"

#include <gtest/gtest.h>

#include <string>

namespace rwd::server {
namespace {

HttpResponse parse_ok(std::string_view bytes) {
  auto response = parse_http_response(bytes);
  EXPECT_TRUE(response.ok()) << response.status().message();
  return response.ok() ? *response : HttpResponse{};
}

std::string refused(std::string_view bytes, ErrorCode code = ErrorCode::kCorrupt) {
  auto response = parse_http_response(bytes, 64);
  EXPECT_FALSE(response.ok()) << "accepted: " << bytes;
  if (response.ok()) return "";
  EXPECT_EQ(response.status().code(), code);
  return response.status().message();
}

TEST(HttpResponse, ContentLength) {
  const HttpResponse r = parse_ok(
      "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\ncontent-length:  2 \r\n\r\n{}");
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.reason, "OK");
  EXPECT_EQ(r.body, "{}");
}

TEST(HttpResponse, Chunked) {
  const HttpResponse r = parse_ok(
      "HTTP/1.1 200 OK\r\nTransfer-Encoding: Chunked\r\n\r\n"
      "4\r\n{\"a\"\r\nA;ext=1\r\n:123456789\r\n0\r\nX-Trailer: yes\r\n\r\n");
  EXPECT_EQ(r.body, "{\"a\":123456789");
}

TEST(HttpResponse, BodyToTheEndAndBodiless) {
  EXPECT_EQ(parse_ok("HTTP/1.0 404 Not Found\r\n\r\nnot found").body, "not found");
  const HttpResponse empty = parse_ok("HTTP/1.1 204 No Content\r\nContent-Length: 0\r\n\r\n");
  EXPECT_EQ(empty.status, 204);
  EXPECT_EQ(empty.body, "");
  EXPECT_EQ(parse_ok("HTTP/1.1 500\r\n\r\n").reason, "");
}

TEST(HttpResponse, MalformedHeadsAreRefused) {
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\n").find("no end of the header section"), std::string::npos);
  EXPECT_NE(refused("HTTP/2 200 OK\r\n\r\n").find("malformed status line"), std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 2x0 OK\r\n\r\n").find("malformed status code"), std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 999 Huh\r\n\r\n").find("out of range"), std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 200OK\r\n\r\n").find("malformed status line"), std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\nNoColon\r\n\r\n").find("without ':'"), std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\nA: 1\r\n folded: x\r\n\r\n").find("header name"),
            std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\nA: x\x01y\r\n\r\n").find("control character"),
            std::string::npos);
}

TEST(HttpResponse, AmbiguousOrTruncatedBodiesAreRefused) {
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\nContent-Length: 5\r\n\r\nabc").find("shorter"),
            std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\nContent-Length: 1\r\n\r\nabc").find("data after"),
            std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\nContent-Length: -1\r\n\r\n").find("Content-Length"),
            std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\nContent-Length: 1\r\nContent-Length: 2\r\n\r\nab")
                .find("conflicting"),
            std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\nContent-Length: 2\r\nTransfer-Encoding: chunked\r\n\r\n"
                    "0\r\n\r\n")
                .find("both"),
            std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: gzip\r\n\r\n").find("unsupported"),
            std::string::npos);
  EXPECT_NE(
      refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\n5\r\nab").find("truncated"),
      std::string::npos);
  EXPECT_NE(
      refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\nzz\r\n").find("chunk size"),
      std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n\r\nextra")
                .find("after the chunked body"),
            std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 204 No Content\r\n\r\nbody").find("has no body"), std::string::npos);
}

TEST(HttpResponse, BodySizeIsBounded) {
  const std::string big(65, 'x');
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\nContent-Length: 65\r\n\r\n" + big, ErrorCode::kCapacity)
                .find("longer than 64"),
            std::string::npos);
  refused("HTTP/1.1 200 OK\r\n\r\n" + big, ErrorCode::kCapacity);
  refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\n41\r\n" + big + "\r\n0\r\n\r\n",
          ErrorCode::kCapacity);
  refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\nfffffffffffffff\r\n",
          ErrorCode::kCapacity);
}

}  // namespace
}  // namespace rwd::server
