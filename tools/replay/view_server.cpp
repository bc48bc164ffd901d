// SPDX-License-Identifier: MIT
#include "view_server.h"

#include <filesystem>
#include <fstream>
#include <iterator>

namespace rwd::replay_tool {
namespace {

std::string content_type_of(const std::string& name) {
  const std::string ext = std::filesystem::path(name).extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".wasm") return "application/wasm";
  return "application/octet-stream";
}

}  // namespace

Result<std::unique_ptr<ViewServer>> ViewServer::open(const std::string& viewer_dir,
                                                     std::vector<uint8_t> bundle,
                                                     const std::string& address, uint16_t port) {
  auto server = std::unique_ptr<ViewServer>(new ViewServer());
  for (const char* name : kViewerFiles) {
    const std::filesystem::path path = std::filesystem::path(viewer_dir) / name;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      return Status::Error(ErrorCode::kNotFound,
                           "the viewer is not built in '" + viewer_dir + "' (no " + name +
                               "): build it with cmake -DREWIND_BUILD_VIEWER=ON and cmake "
                               "--build DIR --target rewind_viewer (needs emscripten: bash "
                               "scripts/setup.sh --viewer), or pass --viewer-dir");
    }
    server->files_.push_back(
        {name, content_type_of(name),
         std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>())});
  }
  server->files_.push_back(
      {"bundle.bin", "application/octet-stream", std::string(bundle.begin(), bundle.end())});
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
  server::HttpReply reply;
  if (request.method != "GET" && request.method != "HEAD") {
    reply.status = 405;
    reply.content_type = "text/plain";
    reply.body = "only GET\n";
    reply.headers.emplace_back("Allow", "GET, HEAD");
    return reply;
  }
  std::string_view path = request.path();
  if (path == "/") path = "/index.html";
  for (const File& file : files_) {
    if (path.size() == file.name.size() + 1 && path.substr(1) == file.name) {
      reply.content_type = file.content_type;
      reply.body = file.body;
      reply.headers.emplace_back("Cache-Control", "no-store");
      return reply;
    }
  }
  reply.status = 404;
  reply.content_type = "text/plain";
  reply.body = "not found\n";
  return reply;
}

}  // namespace rwd::replay_tool
