// SPDX-License-Identifier: MIT
#pragma once
// `rewind-replay view`: serves the browser viewer's files and one view
// bundle over HTTP on loopback (or the address given).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rewind/server/http_endpoint.h"
#include "rewind/sim/status.h"

namespace rwd::replay_tool {

/// The files a viewer directory must hold (the build's viewer_web).
inline constexpr const char* kViewerFiles[] = {
    "index.html", "viewer.js",        "render.js",         "camera.js",
    "viewer.css", "rewind_viewer.js", "rewind_viewer.wasm"};

/// The viewer's HTTP server: GET / (index.html), GET /<one of
/// kViewerFiles> and GET /bundle.bin; anything else is 404, any method
/// but GET (and HEAD) 405. Files are read once, at open().
class ViewServer {
 public:
  /// kNotFound naming the first missing file when `viewer_dir` is not a
  /// built viewer; the endpoint's errors for the address and port.
  static Result<std::unique_ptr<ViewServer>> open(const std::string& viewer_dir,
                                                  std::vector<uint8_t> bundle,
                                                  const std::string& address, uint16_t port);
  uint16_t port() const { return endpoint_->port(); }
  void close() { endpoint_->close(); }

 private:
  struct File {
    std::string name;
    std::string content_type;
    std::string body;
  };
  server::HttpReply answer(const server::HttpRequest& request) const;

  std::vector<File> files_;
  std::unique_ptr<server::HttpEndpoint> endpoint_;
};

}  // namespace rwd::replay_tool
