// SPDX-License-Identifier: MIT
#include "rewind/server/match_environment.h"

#include <chrono>
#include <filesystem>
#include <fstream>

namespace rwd::server {

MatchEnvironment MatchEnvironment::os() {
  MatchEnvironment env;
  env.unix_ms = [] {
    return static_cast<int64_t>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                    std::chrono::system_clock::now().time_since_epoch())
                                    .count());
  };
  env.create_directories = [](const std::string& path) {
    std::error_code error;
    std::filesystem::create_directories(path, error);
    if (error) {
      return Status::Error(ErrorCode::kIo,
                           "cannot create directory '" + path + "': " + error.message());
    }
    return Status::Ok();
  };
  env.write_file = [](const std::string& path, std::span<const uint8_t> bytes) {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
    file.close();
    if (!file) return Status::Error(ErrorCode::kIo, "cannot write '" + path + "'");
    return Status::Ok();
  };
  return env;
}

}  // namespace rwd::server
