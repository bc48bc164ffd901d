// SPDX-License-Identifier: MIT
#pragma once
// A strict JSON reader (RFC 8259) for the small documents the server reads
// from its orchestrator (the Agones GameServer). Everything the RFC forbids
// is refused: trailing commas, comments, leading zeros, lone surrogates,
// invalid UTF-8, control characters in strings, duplicate object keys,
// anything after the value. Input size and nesting depth are bounded, so a
// hostile document costs at most its bytes and a fixed stack.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/sim/status.h"

namespace rwd::server {

struct JsonLimits {
  /// Longer input is refused before parsing.
  size_t max_bytes = 1 << 20;
  /// Arrays and objects nested deeper than this are refused; the top-level
  /// value is depth 1.
  int max_depth = 32;
};

/// One parsed JSON value; owns its children. Accessors for the wrong kind
/// return an empty value (false, 0, "", no items) rather than failing, so
/// callers check kind() where the shape matters.
class JsonValue {
 public:
  enum class Kind : uint8_t { kNull, kBool, kNumber, kString, kArray, kObject };

  static JsonValue null() { return JsonValue(Kind::kNull); }
  static JsonValue boolean(bool value);
  static JsonValue number(double value);
  static JsonValue string(std::string value);
  static JsonValue array(std::vector<JsonValue> items);
  /// `keys` and `values` pair up by index (same length); keys are unique.
  static JsonValue object(std::vector<std::string> keys, std::vector<JsonValue> values);

  Kind kind() const { return kind_; }
  bool is(Kind kind) const { return kind_ == kind; }
  bool as_bool() const { return bool_; }
  /// A finite double (numbers beyond its range are refused by parse_json).
  double as_number() const { return number_; }
  /// UTF-8, escapes resolved.
  const std::string& as_string() const { return string_; }
  /// An array's items, or an object's values in document order.
  const std::vector<JsonValue>& items() const { return items_; }
  /// An object's keys in document order (empty for other kinds).
  const std::vector<std::string>& keys() const { return keys_; }
  /// The value of `key` in an object; null when absent or not an object.
  /// Valid while this value lives.
  const JsonValue* find(std::string_view key) const;

  friend bool operator==(const JsonValue&, const JsonValue&) = default;

 private:
  explicit JsonValue(Kind kind) : kind_(kind) {}

  Kind kind_ = Kind::kNull;
  bool bool_ = false;
  double number_ = 0;
  std::string string_;
  std::vector<std::string> keys_;
  std::vector<JsonValue> items_;
};

/// Parses one JSON document (surrounding whitespace allowed). Errors are
/// kCorrupt with a message naming what is wrong and its byte offset, or
/// kCapacity when `text` is larger than limits.max_bytes.
Result<JsonValue> parse_json(std::string_view text, const JsonLimits& limits = {});

/// The name of a kind, for error messages ("object", "string", ...).
std::string_view json_kind_name(JsonValue::Kind kind);

}  // namespace rwd::server
