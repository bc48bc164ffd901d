// SPDX-License-Identifier: MIT
#include "rewind/server/api_keys.h"

#include <sodium.h>

#include <cstdio>

namespace rwd::server {
namespace {

constexpr size_t kMinKeyChars = 32;
constexpr size_t kMaxKeyChars = 256;
constexpr size_t kMaxNameChars = 64;
constexpr size_t kMaxFileBytes = 64 * 1024;

std::array<uint8_t, 32> digest_of(std::string_view key) {
  std::array<uint8_t, 32> out{};
  crypto_generichash(out.data(), out.size(), reinterpret_cast<const unsigned char*>(key.data()),
                     key.size(), nullptr, 0);
  return out;
}

bool is_name(std::string_view text) {
  if (text.empty() || text.size() > kMaxNameChars) return false;
  for (const char c : text) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '.' || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

bool is_key(std::string_view text) {
  if (text.size() < kMinKeyChars || text.size() > kMaxKeyChars) return false;
  for (const char c : text) {
    if (c <= 0x20 || c >= 0x7f) return false;
  }
  return true;
}

// Splits `line` at spaces and tabs.
std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  size_t at = 0;
  while (at < line.size()) {
    while (at < line.size() && (line[at] == ' ' || line[at] == '\t')) ++at;
    size_t end = at;
    while (end < line.size() && line[end] != ' ' && line[end] != '\t') ++end;
    if (end > at) out.push_back(line.substr(at, end - at));
    at = end;
  }
  return out;
}

bool equal_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c + 32) : c; };
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

}  // namespace

Result<ApiKeys> ApiKeys::parse(std::string_view text) {
  if (sodium_init() < 0) return Status::Error(ErrorCode::kUnsupported, "libsodium failed to start");
  ApiKeys keys;
  size_t line_number = 0;
  while (!text.empty()) {
    const size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::vector<std::string_view> fields = words(line);
    if (fields.empty() || fields.front().front() == '#') continue;
    const auto bad = [&](const std::string& why) {
      return Status::Error(ErrorCode::kInvalidArgument,
                           "line " + std::to_string(line_number) + ": " + why);
    };
    if (fields.size() < 2 || fields.size() > 3) return bad("expected NAME KEY [admin]");
    if (!is_name(fields[0])) return bad("a name is 1 to 64 characters of A-Z a-z 0-9 . _ -");
    if (!is_key(fields[1])) {
      return bad("a key is 32 to 256 visible characters (rewind-token api-key makes one)");
    }
    if (fields.size() == 3 && fields[2] != "admin") {
      return bad("the role, when given, is 'admin'");
    }
    Entry entry;
    entry.digest = digest_of(fields[1]);
    entry.caller.name = std::string(fields[0]);
    entry.caller.admin = fields.size() == 3;
    for (const Entry& other : keys.entries_) {
      if (other.caller.name == entry.caller.name) {
        return bad("name '" + entry.caller.name + "' given twice");
      }
      if (other.digest == entry.digest) return bad("a key given twice");
    }
    keys.entries_.push_back(std::move(entry));
  }
  if (keys.entries_.empty()) return Status::Error(ErrorCode::kInvalidArgument, "no keys in it");
  return keys;
}

Result<ApiKeys> ApiKeys::load(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return Status::Error(ErrorCode::kIo, path + ": cannot read it");
  std::string text(kMaxFileBytes + 1, '\0');
  const size_t read = std::fread(text.data(), 1, text.size(), file);
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed) return Status::Error(ErrorCode::kIo, path + ": cannot read it");
  if (read > kMaxFileBytes) {
    return Status::Error(ErrorCode::kInvalidArgument, path + ": larger than 64 KiB");
  }
  text.resize(read);
  auto keys = parse(text);
  if (!keys.ok()) return Status::Error(keys.status().code(), path + ": " + keys.status().message());
  return keys;
}

std::optional<ApiCaller> ApiKeys::authenticate(std::string_view authorization) const {
  constexpr std::string_view kScheme = "Bearer ";
  if (authorization.size() <= kScheme.size() ||
      !equal_ignoring_case(authorization.substr(0, kScheme.size()), kScheme)) {
    return std::nullopt;
  }
  std::string_view key = authorization.substr(kScheme.size());
  while (!key.empty() && (key.front() == ' ' || key.front() == '\t')) key.remove_prefix(1);
  while (!key.empty() && (key.back() == ' ' || key.back() == '\t')) key.remove_suffix(1);
  // Every entry is compared, whichever matches: the time taken says nothing
  // about which key, or how much of one, was right.
  const std::array<uint8_t, 32> digest = digest_of(key);
  const Entry* found = nullptr;
  for (const Entry& entry : entries_) {
    const bool same = sodium_memcmp(entry.digest.data(), digest.data(), digest.size()) == 0;
    if (same) found = &entry;
  }
  if (found == nullptr) return std::nullopt;
  return found->caller;
}

}  // namespace rwd::server
