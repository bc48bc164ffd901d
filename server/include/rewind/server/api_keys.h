// SPDX-License-Identifier: MIT
#pragma once
// Bearer keys for the server's HTTP endpoints (the control API, /metrics),
// read from a file the operator provisions, one caller a line:
//
//   # name    key (32 to 256 visible characters)                          role
//   backend   4f0c3a9e5d1b7c2a8e6f0d4b3a291c7e5f8a0b6d2c4e1f3a5b7c9d0e2f4a6b8c
//   ops       9d2e41b07c5a3f1e8d6c4b2a0f9e7d5c3b1a2f4e6d8c0b9a7e5f3d1c2b4a6e8f  admin
//
// `rewind-token api-key` prints such a line. A request names its caller by
// sending `Authorization: Bearer <key>`. Keys are kept only as BLAKE2b
// digests and every entry is compared in constant time, so neither the
// answer's timing nor memory holds a key or says how much of one matched.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/core/status.h"

namespace rwd::server {

/// Who a request comes from.
struct ApiCaller {
  std::string name;    ///< the file's first column: [A-Za-z0-9_.-], 1 to 64 characters
  bool admin = false;  ///< role "admin": may stop any match
};

class ApiKeys {
 public:
  /// Reads the file's text: blank lines and '#' comments skipped; names and
  /// keys unique. kInvalidArgument names the first bad line.
  static Result<ApiKeys> parse(std::string_view text);
  /// Reads `path` (at most 64 KiB). kIo when it cannot be read, else as
  /// parse(), with the path in the message.
  static Result<ApiKeys> load(const std::string& path);

  /// The caller whose key `authorization` carries ("Bearer <key>", the
  /// scheme case-insensitive); nullopt for no header, another scheme or an
  /// unknown key. Takes the same time whichever entry matches.
  std::optional<ApiCaller> authenticate(std::string_view authorization) const;

  size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    std::array<uint8_t, 32> digest{};
    ApiCaller caller;
  };
  std::vector<Entry> entries_;
};

}  // namespace rwd::server
