// SPDX-License-Identifier: MIT
#pragma once
// `rewind-replay view`: serves the browser viewer's files and one view
// bundle over HTTP on loopback (or the address given).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/server/http_endpoint.h"
#include "rewind/server/static_files.h"

namespace rwd::replay_tool {

/// The viewer's HTTP server: GET / (index.html), GET /<one of
/// server::kViewerFiles> and GET /bundle.bin; anything else is 404, any
/// method but GET (and HEAD) 405. Files are read once, at open().
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
  explicit ViewServer(server::StaticFiles files) : files_(std::move(files)) {}
  server::HttpReply answer(const server::HttpRequest& request) const;

  server::StaticFiles files_;
  std::unique_ptr<server::HttpEndpoint> endpoint_;
};

}  // namespace rwd::replay_tool
