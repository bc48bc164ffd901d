// SPDX-License-Identifier: MIT
#pragma once
// Files an HTTP endpoint serves as they are: read once from a directory,
// answered by name with their content type. The browser viewer's page and
// engine (the build's viewer_web) are served this way by `rewind-replay
// view` and by the server's live endpoint.
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/server/http_endpoint.h"

namespace rwd::server {

/// The files a built viewer directory holds (the build's viewer_web).
inline constexpr const char* kViewerFiles[] = {
    "index.html", "viewer.js",  "live.js",          "render.js",
    "camera.js",  "viewer.css", "rewind_viewer.js", "rewind_viewer.wasm"};

class StaticFiles {
 public:
  /// Reads `names` from `dir`; kNotFound naming the first missing file.
  static Result<StaticFiles> load(const std::string& dir, std::span<const char* const> names);
  /// The built viewer in `dir`; kNotFound says how to build it.
  static Result<StaticFiles> load_viewer(const std::string& dir);

  /// Adds (or replaces) one file held in memory.
  void add(std::string name, std::string content_type, std::string body);
  /// The reply for GET `path` ("/<name>"), or nullopt when no file has
  /// that name. Never cached by the browser: a rebuilt viewer shows at once.
  std::optional<HttpReply> find(std::string_view path) const;

 private:
  struct File {
    std::string name;
    std::string content_type;
    std::string body;
  };
  std::vector<File> files_;
};

/// Where the browser viewer is when no directory is given: installed next
/// to the running program (PREFIX/share/rewind/viewer for PREFIX/bin), else
/// the build's viewer_web when it was built; empty when neither holds one.
std::string default_viewer_dir();

/// The reply to a method other than GET or HEAD: 405 with an Allow header.
HttpReply method_not_allowed();
/// A plain-text reply with `status`, e.g. 404 "not found".
HttpReply text_reply(unsigned status, std::string text);

}  // namespace rwd::server
