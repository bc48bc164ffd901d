// SPDX-License-Identifier: MIT
#include "rewind/server/agones_sdk.h"

#include "rewind/server/http_client.h"

namespace rwd::server {

Result<uint16_t> agones_port_from_env(const char* value) {
  if (value == nullptr) return kAgonesDefaultHttpPort;
  const std::string_view text(value);
  uint32_t port = 0;
  bool valid = !text.empty() && text.size() <= 5;
  for (const char c : text) {
    if (c < '0' || c > '9') valid = false;
    if (valid) port = port * 10 + static_cast<uint32_t>(c - '0');
  }
  if (!valid || port < 1 || port > 65535) {
    return Status::Error(ErrorCode::kInvalidArgument, "AGONES_SDK_HTTP_PORT='" + std::string(text) +
                                                          "' is not a port number in [1, 65535]");
  }
  return static_cast<uint16_t>(port);
}

Result<std::string> AgonesSdk::call(std::string_view method, std::string_view path) const {
  HttpCallRequest request;
  request.method = std::string(method);
  request.target = std::string(path);
  // The REST gateway's lifecycle calls take an empty message.
  if (method != "GET") request.body = "{}";
  HttpCallLimits limits;
  limits.deadline = options_.call_deadline;
  limits.response.max_body_bytes = kAgonesGameServerMaxBytes;
  auto response = http_call(options_.host, options_.port, request, limits);
  if (!response.ok()) return response.status();
  if (response->status < 200 || response->status > 299) {
    std::string body = response->body.substr(0, 200);
    for (char& c : body) {
      if (static_cast<unsigned char>(c) < 0x20) c = ' ';
    }
    return Status::Error(ErrorCode::kIo, std::string(method) + " " + std::string(path) + ": HTTP " +
                                             std::to_string(response->status) + " " +
                                             response->reason + (body.empty() ? "" : ": " + body));
  }
  return std::move(response->body);
}

Status AgonesSdk::ready() const {
  return call("POST", "/ready").status();
}

Status AgonesSdk::health() const {
  return call("POST", "/health").status();
}

Status AgonesSdk::shutdown() const {
  return call("POST", "/shutdown").status();
}

Result<AgonesGameServer> AgonesSdk::game_server() const {
  auto body = call("GET", "/gameserver");
  if (!body.ok()) return body.status();
  return parse_agones_game_server(*body);
}

}  // namespace rwd::server
