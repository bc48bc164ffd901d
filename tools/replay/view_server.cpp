// SPDX-License-Identifier: MIT
#include "view_server.h"

namespace rwd::replay_tool {

Result<std::unique_ptr<ViewServer>> ViewServer::open(const std::string& viewer_dir,
                                                     std::vector<uint8_t> bundle,
                                                     const std::string& address, uint16_t port) {
  auto files = server::StaticFiles::load_viewer(viewer_dir);
  if (!files.ok()) return files.status();
  auto server = std::unique_ptr<ViewServer>(new ViewServer(std::move(*files)));
  server->files_.add("bundle.bin", "application/octet-stream",
                     std::string(bundle.begin(), bundle.end()));
  server::HttpEndpointLimits limits;
  limits.deadline = std::chrono::milliseconds(20000);  // a bundle of hours of play is megabytes
  const ViewServer* self = server.get();
  auto endpoint = server::HttpEndpoint::open(
      "viewer", address, port,
      [self](const server::HttpRequest& request) { return self->answer(request); }, limits);
  if (!endpoint.ok()) return endpoint.status();
  server->endpoint_ = std::move(*endpoint);
  return server;
}

server::HttpReply ViewServer::answer(const server::HttpRequest& request) const {
  if (request.method != "GET" && request.method != "HEAD") return server::method_not_allowed();
  const std::string_view path = request.path();
  if (auto file = files_.find(path == "/" ? "/index.html" : path)) return *file;
  return server::text_reply(404, "not found\n");
}

}  // namespace rwd::replay_tool
