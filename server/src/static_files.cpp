// SPDX-License-Identifier: MIT
#include "rewind/server/static_files.h"

#include <filesystem>
#include <fstream>
#include <iterator>

namespace rwd::server {
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

Result<StaticFiles> StaticFiles::load(const std::string& dir, std::span<const char* const> names) {
  StaticFiles files;
  for (const char* name : names) {
    const std::filesystem::path path = std::filesystem::path(dir) / name;
    std::ifstream in(path, std::ios::binary);
    if (!in) return Status::Error(ErrorCode::kNotFound, "no " + path.string());
    files.add(name, content_type_of(name),
              std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()));
  }
  return files;
}

std::string default_viewer_dir() {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    const fs::path installed = program.parent_path().parent_path() / "share" / "rewind" / "viewer";
    if (fs::exists(installed / "index.html", error)) return installed.string();
  }
  const fs::path built = REWIND_BUILD_VIEWER_DIR;
  if (fs::exists(built / "index.html", error)) return built.string();
  return {};
}

Result<StaticFiles> StaticFiles::load_viewer(const std::string& dir) {
  auto files = load(dir, kViewerFiles);
  if (files.ok()) return files;
  if (dir.empty()) {
    return Status::Error(
        ErrorCode::kNotFound,
        "no browser viewer is installed or built: build it with cmake "
        "-DREWIND_BUILD_VIEWER=ON and cmake --build DIR --target rewind_viewer "
        "(needs emscripten: bash scripts/setup.sh --viewer), or pass --viewer-dir");
  }
  return Status::Error(ErrorCode::kNotFound,
                       "the viewer is not built in '" + dir + "' (" + files.status().message() +
                           "): build it with cmake -DREWIND_BUILD_VIEWER=ON and cmake --build "
                           "DIR --target rewind_viewer (needs emscripten: bash scripts/setup.sh "
                           "--viewer), or pass --viewer-dir");
}

void StaticFiles::add(std::string name, std::string content_type, std::string body) {
  for (File& file : files_) {
    if (file.name == name) {
      file.content_type = std::move(content_type);
      file.body = std::move(body);
      return;
    }
  }
  files_.push_back({std::move(name), std::move(content_type), std::move(body)});
}

std::optional<HttpReply> StaticFiles::find(std::string_view path) const {
  for (const File& file : files_) {
    if (path.size() == file.name.size() + 1 && path.front() == '/' && path.substr(1) == file.name) {
      HttpReply reply;
      reply.content_type = file.content_type;
      reply.body = file.body;
      reply.headers.emplace_back("Cache-Control", "no-store");
      return reply;
    }
  }
  return std::nullopt;
}

HttpReply method_not_allowed() {
  HttpReply reply = text_reply(405, "only GET\n");
  reply.headers.emplace_back("Allow", "GET, HEAD");
  return reply;
}

HttpReply text_reply(unsigned status, std::string text) {
  HttpReply reply;
  reply.status = status;
  reply.content_type = "text/plain; charset=utf-8";
  reply.body = std::move(text);
  return reply;
}

}  // namespace rwd::server
