// SPDX-License-Identifier: MIT
// The HTTP client: reading whole responses through its parser (each body
// framing, and the malformed or ambiguous responses that must be refused),
// and calls against a loopback server: the request it sends, and each way
// a call can fail, named.
#include "rewind/server/http_client.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "local_http_server.h"

namespace rwd::server {
namespace {

using testing::LocalHttpServer;

HttpResponse parse_ok(std::string_view bytes) {
  auto response = parse_http_response(bytes);
  EXPECT_TRUE(response.ok()) << response.status().message();
  return response.ok() ? *response : HttpResponse{};
}

// The message for `bytes`, refused with `code` when the body may hold 64.
std::string refused(std::string_view bytes, ErrorCode code = ErrorCode::kCorrupt) {
  HttpResponseLimits limits;
  limits.max_body_bytes = 64;
  limits.max_header_bytes = 256;
  auto response = parse_http_response(bytes, limits);
  EXPECT_FALSE(response.ok()) << "accepted: " << bytes;
  if (response.ok()) return "";
  EXPECT_EQ(response.status().code(), code) << bytes;
  return response.status().message();
}

TEST(HttpResponse, ContentLength) {
  const HttpResponse r = parse_ok(
      "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\ncontent-length:  2 \r\n\r\n{}");
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.reason, "OK");
  EXPECT_EQ(r.body, "{}");
  // The client never reads past the response it asked for.
  EXPECT_EQ(parse_ok("HTTP/1.1 200 OK\r\nContent-Length: 1\r\n\r\nabc").body, "a");
}

TEST(HttpResponse, Chunked) {
  const HttpResponse r = parse_ok(
      "HTTP/1.1 200 OK\r\nTransfer-Encoding: Chunked\r\n\r\n"
      "4\r\n{\"a\"\r\nA;ext=1\r\n:123456789\r\n0\r\nX-Trailer: yes\r\n\r\n");
  EXPECT_EQ(r.body, "{\"a\":123456789");
}

TEST(HttpResponse, BodyToTheEndAndBodiless) {
  EXPECT_EQ(parse_ok("HTTP/1.0 404 Not Found\r\n\r\nnot found").body, "not found");
  EXPECT_EQ(parse_ok("HTTP/1.1 200 OK\r\n\r\n").body, "");
  const HttpResponse empty = parse_ok("HTTP/1.1 204 No Content\r\nContent-Length: 0\r\n\r\n");
  EXPECT_EQ(empty.status, 204);
  EXPECT_EQ(empty.body, "");
  // These never carry a body, whatever follows.
  EXPECT_EQ(parse_ok("HTTP/1.1 304 Not Modified\r\nContent-Length: 4\r\n\r\nbody").body, "");
  EXPECT_EQ(parse_ok("HTTP/1.1 500 \r\n\r\n").status, 500);
}

TEST(HttpResponse, MalformedHeadsAreRefused) {
  EXPECT_EQ(refused(""), "HTTP response: the connection closed before a response");
  EXPECT_EQ(refused("HTTP/1.1 200 OK\r\n"), "HTTP response: the connection closed mid-response");
  EXPECT_EQ(refused("SSH-2.0-x\r\n\r\n"), "HTTP response: malformed response: bad version");
  EXPECT_EQ(refused("HTTP/2 200 OK\r\n\r\n"), "HTTP response: malformed response: bad version");
  EXPECT_EQ(refused("HTTP/1.1 2x0 OK\r\n\r\n"), "HTTP response: malformed response: bad status");
  EXPECT_EQ(refused("HTTP/1.1 999 Huh\r\n\r\n"), "HTTP response: status code 999 out of range");
  EXPECT_EQ(refused("HTTP/1.1 099 Huh\r\n\r\n"), "HTTP response: status code 99 out of range");
  EXPECT_NE(refused("HTTP/1.1 200OK\r\n\r\n").find("malformed response"), std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\nNoColon\r\n\r\n").find("malformed response"),
            std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 200 OK\nA: 1\n\n").find("malformed response"), std::string::npos);
  EXPECT_NE(refused("HTTP/1.1 200 OK\r\nA: x\x01y\r\n\r\n").find("malformed response: bad value"),
            std::string::npos);
}

TEST(HttpResponse, AmbiguousOrTruncatedBodiesAreRefused) {
  EXPECT_EQ(refused("HTTP/1.1 200 OK\r\nContent-Length: 5\r\n\r\nabc"),
            "HTTP response: the connection closed mid-response");
  EXPECT_EQ(refused("HTTP/1.1 200 OK\r\nContent-Length: -1\r\n\r\n"),
            "HTTP response: malformed response: bad Content-Length");
  EXPECT_EQ(refused("HTTP/1.1 200 OK\r\nContent-Length: 1\r\nContent-Length: 2\r\n\r\nab"),
            "HTTP response: malformed response: multiple Content-Length");
  EXPECT_EQ(refused("HTTP/1.1 200 OK\r\nContent-Length: 2\r\nTransfer-Encoding: chunked\r\n\r\n"
                    "0\r\n\r\n"),
            "HTTP response: malformed response: bad Transfer-Encoding");
  EXPECT_EQ(refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\nContent-Length: 2\r\n\r\n"
                    "0\r\n\r\n"),
            "HTTP response: malformed response: bad Content-Length");
  EXPECT_EQ(refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: gzip\r\n\r\nxyz"),
            "HTTP response: unsupported Transfer-Encoding");
  EXPECT_EQ(refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: gzip, chunked\r\n\r\n0\r\n\r\n"),
            "HTTP response: unsupported Transfer-Encoding");
  EXPECT_EQ(refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\n5\r\nab"),
            "HTTP response: the connection closed mid-response");
  EXPECT_EQ(refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\nzz\r\n"),
            "HTTP response: malformed response: bad chunk");
}

TEST(HttpResponse, SizesAreBounded) {
  const std::string big(65, 'x');
  EXPECT_EQ(refused("HTTP/1.1 200 OK\r\nContent-Length: 65\r\n\r\n" + big, ErrorCode::kCapacity),
            "HTTP response: body longer than 64 bytes");
  refused("HTTP/1.1 200 OK\r\n\r\n" + big, ErrorCode::kCapacity);
  refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\n41\r\n" + big + "\r\n0\r\n\r\n",
          ErrorCode::kCapacity);
  refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\n20\r\n" + std::string(32, 'x') +
              "\r\n21\r\n" + std::string(33, 'x') + "\r\n0\r\n\r\n",
          ErrorCode::kCapacity);
  refused("HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\nfffffffffffffff\r\n",
          ErrorCode::kCapacity);
  EXPECT_EQ(
      refused("HTTP/1.1 200 OK\r\nX: " + std::string(300, 'h') + "\r\n\r\n", ErrorCode::kCapacity),
      "HTTP response: header section longer than 256 bytes");
}

HttpCallLimits quick(std::chrono::milliseconds deadline = std::chrono::seconds(2)) {
  HttpCallLimits limits;
  limits.deadline = deadline;
  return limits;
}

std::string context(const char* call, uint16_t port) {
  return std::string("HTTP ") + call + " to 127.0.0.1:" + std::to_string(port) + ": ";
}

TEST(HttpCall, SendsOneRequestAndReadsTheAnswer) {
  LocalHttpServer server([](const std::string&) {
    return std::string(
        "HTTP/1.1 201 Created\r\nTransfer-Encoding: chunked\r\n\r\n3\r\n{\"a\r\n3\r\n\":1\r\n1\r\n}"
        "\r\n0\r\n\r\n");
  });
  HttpCallRequest request;
  request.method = "PATCH";
  request.target = "/x?y=1";
  request.body = "{\"b\":2}";
  auto response = http_call("127.0.0.1", server.port(), request, quick());
  ASSERT_TRUE(response.ok()) << response.status().message();
  EXPECT_EQ(response->status, 201);
  EXPECT_EQ(response->reason, "Created");
  EXPECT_EQ(response->body, "{\"a\":1}");
  const std::string sent = server.requests().at(0);
  EXPECT_EQ(sent.rfind("PATCH /x?y=1 HTTP/1.1\r\n", 0), 0u) << sent;
  EXPECT_NE(sent.find("Host: 127.0.0.1:" + std::to_string(server.port()) + "\r\n"),
            std::string::npos);
  EXPECT_NE(sent.find("Accept: application/json\r\n"), std::string::npos);
  EXPECT_NE(sent.find("Content-Type: application/json\r\n"), std::string::npos);
  EXPECT_NE(sent.find("Content-Length: 7\r\n"), std::string::npos);
  EXPECT_NE(sent.find("Connection: close\r\n"), std::string::npos);
  EXPECT_EQ(sent.substr(sent.size() - 11), "\r\n\r\n{\"b\":2}");
}

TEST(HttpCall, AnAnswerInManyReadsComesWhole) {
  std::string body(300'000, 'x');
  for (size_t i = 0; i < body.size(); i += 997) body[i] = static_cast<char>('a' + i % 26);
  LocalHttpServer server([&body](const std::string&) {
    // Padding headers too, so the head itself may span reads.
    return "HTTP/1.1 200 OK\r\nX-Pad: " + std::string(8000, 'p') +
           "\r\nContent-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
  });
  auto response = http_call("127.0.0.1", server.port(), HttpCallRequest{}, quick());
  ASSERT_TRUE(response.ok()) << response.status().message();
  EXPECT_EQ(response->body, body);
}

TEST(HttpCall, MalformedRequestsAreNotSent) {
  HttpCallRequest request;
  request.method = "get";
  EXPECT_EQ(http_call("127.0.0.1", 1, request).status().code(), ErrorCode::kInvalidArgument);
  request.method = "GET";
  for (const char* target : {"", "x", "/a b", "/a\r\nX: 1", "/\x7f"}) {
    request.target = target;
    const Status status = http_call("127.0.0.1", 1, request).status();
    EXPECT_EQ(status.code(), ErrorCode::kInvalidArgument) << target;
    EXPECT_EQ(status.message(), "HTTP: malformed target '" + std::string(target) + "'");
  }
}

TEST(HttpCall, BrokenAnswersNameTheCall) {
  LocalHttpServer cut([](const std::string&) {
    return std::string("HTTP/1.1 200 OK\r\nContent-Length: 10\r\n\r\nabc");
  });
  Status status = http_call("127.0.0.1", cut.port(), HttpCallRequest{}, quick()).status();
  EXPECT_EQ(status.code(), ErrorCode::kCorrupt);
  EXPECT_EQ(status.message(), context("GET /", cut.port()) + "the connection closed mid-response");

  LocalHttpServer garbled([](const std::string&) { return std::string("SSH-2.0-x\r\n\r\n"); });
  status = http_call("127.0.0.1", garbled.port(), HttpCallRequest{}, quick()).status();
  EXPECT_EQ(status.code(), ErrorCode::kCorrupt);
  EXPECT_EQ(status.message(), context("GET /", garbled.port()) + "malformed response: bad version");

  LocalHttpServer flood([](const std::string&) {
    return LocalHttpServer::json_answer("200 OK", std::string(100, 'x'));
  });
  HttpCallLimits small = quick();
  small.response.max_body_bytes = 99;
  status = http_call("127.0.0.1", flood.port(), HttpCallRequest{}, small).status();
  EXPECT_EQ(status.code(), ErrorCode::kCapacity);
  EXPECT_EQ(status.message(), context("GET /", flood.port()) + "body longer than 99 bytes");
}

TEST(HttpCall, UnresolvableHostIsAnIoError) {
  const Status status = http_call("no-such-host.invalid", 80, HttpCallRequest{}, quick()).status();
  EXPECT_EQ(status.code(), ErrorCode::kIo);
  EXPECT_EQ(status.message().rfind("HTTP GET / to no-such-host.invalid:80: resolve: ", 0), 0u)
      << status.message();
}

TEST(HttpCall, ASilentPeerTimesOutAtTheDeadline) {
  LocalHttpServer silent([](const std::string&) { return std::string(); });
  const auto start = std::chrono::steady_clock::now();
  const Status status = http_call("127.0.0.1", silent.port(), HttpCallRequest{},
                                  quick(std::chrono::milliseconds(150)))
                            .status();
  const auto took = std::chrono::steady_clock::now() - start;
  EXPECT_EQ(status.code(), ErrorCode::kIo);
  EXPECT_EQ(status.message(), context("GET /", silent.port()) + "read: no answer within 150 ms");
  EXPECT_GE(took, std::chrono::milliseconds(140));
  EXPECT_LT(took, std::chrono::seconds(2));
}

}  // namespace
}  // namespace rwd::server
