// SPDX-License-Identifier: MIT
#include "rewind/server/json_value.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <system_error>
#include <utility>

namespace rwd::server {

JsonValue JsonValue::boolean(bool value) {
  JsonValue v(Kind::kBool);
  v.bool_ = value;
  return v;
}

JsonValue JsonValue::number(double value) {
  JsonValue v(Kind::kNumber);
  v.number_ = value;
  return v;
}

JsonValue JsonValue::string(std::string value) {
  JsonValue v(Kind::kString);
  v.string_ = std::move(value);
  return v;
}

JsonValue JsonValue::array(std::vector<JsonValue> items) {
  JsonValue v(Kind::kArray);
  v.items_ = std::move(items);
  return v;
}

JsonValue JsonValue::object(std::vector<std::string> keys, std::vector<JsonValue> values) {
  JsonValue v(Kind::kObject);
  v.keys_ = std::move(keys);
  v.items_ = std::move(values);
  return v;
}

const JsonValue* JsonValue::find(std::string_view key) const {
  if (kind_ != Kind::kObject) return nullptr;
  for (size_t i = 0; i < keys_.size(); ++i) {
    if (keys_[i] == key) return &items_[i];
  }
  return nullptr;
}

std::string_view json_kind_name(JsonValue::Kind kind) {
  switch (kind) {
    case JsonValue::Kind::kNull:
      return "null";
    case JsonValue::Kind::kBool:
      return "boolean";
    case JsonValue::Kind::kNumber:
      return "number";
    case JsonValue::Kind::kString:
      return "string";
    case JsonValue::Kind::kArray:
      return "array";
    case JsonValue::Kind::kObject:
      return "object";
  }
  return "value";
}

namespace {

// Recursive descent over the text. Recursion is bounded by the depth limit;
// the first error is kept and every caller unwinds at once.
class Parser {
 public:
  Parser(std::string_view text, int max_depth) : text_(text), max_depth_(max_depth) {}

  Result<JsonValue> document() {
    skip_space();
    JsonValue value = parse_value(1);
    if (failed()) return error_;
    skip_space();
    if (pos_ != text_.size()) {
      fail_at("unexpected data after the value");
      return error_;
    }
    return value;
  }

 private:
  bool failed() const { return !error_.ok(); }

  void fail_at(std::string_view what) {
    if (failed()) return;
    error_ = Status::Error(ErrorCode::kCorrupt,
                           "JSON: " + std::string(what) + " at byte " + std::to_string(pos_));
  }

  JsonValue fail(std::string_view what) {
    fail_at(what);
    return JsonValue::null();
  }

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }

  void skip_space() {
    while (!at_end()) {
      const char c = text_[pos_];
      if (c != ' ' && c != '\t' && c != '\n' && c != '\r') return;
      ++pos_;
    }
  }

  bool consume_word(std::string_view word) {
    if (text_.substr(pos_, word.size()) != word) return false;
    pos_ += word.size();
    return true;
  }

  JsonValue parse_value(int depth) {
    if (at_end()) return fail("unexpected end of input");
    switch (peek()) {
      case '{':
        return parse_object(depth);
      case '[':
        return parse_array(depth);
      case '"': {
        std::string text = parse_string();
        return JsonValue::string(std::move(text));
      }
      case 't':
        if (consume_word("true")) return JsonValue::boolean(true);
        break;
      case 'f':
        if (consume_word("false")) return JsonValue::boolean(false);
        break;
      case 'n':
        if (consume_word("null")) return JsonValue::null();
        break;
      default:
        if (peek() == '-' || (peek() >= '0' && peek() <= '9')) return parse_number();
        break;
    }
    return fail("unexpected character");
  }

  bool enter(int depth) {
    if (depth > max_depth_) {
      fail_at("nesting deeper than " + std::to_string(max_depth_));
      return false;
    }
    ++pos_;  // the opening bracket
    skip_space();
    return true;
  }

  JsonValue parse_array(int depth) {
    if (!enter(depth)) return JsonValue::null();
    std::vector<JsonValue> items;
    if (peek() == ']') {
      ++pos_;
      return JsonValue::array(std::move(items));
    }
    while (!failed()) {
      items.push_back(parse_value(depth + 1));
      if (failed()) break;
      skip_space();
      if (peek() == ',') {
        ++pos_;
        skip_space();
        continue;
      }
      if (peek() == ']') {
        ++pos_;
        return JsonValue::array(std::move(items));
      }
      fail_at(at_end() ? "unterminated array" : "expected ',' or ']'");
    }
    return JsonValue::null();
  }

  JsonValue parse_object(int depth) {
    const size_t start = pos_;
    if (!enter(depth)) return JsonValue::null();
    std::vector<std::string> keys;
    std::vector<JsonValue> values;
    if (peek() == '}') {
      ++pos_;
      return JsonValue::object(std::move(keys), std::move(values));
    }
    while (!failed()) {
      if (peek() != '"') {
        fail_at(at_end() ? "unterminated object" : "expected a string key");
        break;
      }
      keys.push_back(parse_string());
      skip_space();
      if (!failed() && peek() != ':') fail_at("expected ':' after a key");
      if (failed()) break;
      ++pos_;
      skip_space();
      values.push_back(parse_value(depth + 1));
      if (failed()) break;
      skip_space();
      if (peek() == ',') {
        ++pos_;
        skip_space();
        continue;
      }
      if (peek() == '}') {
        ++pos_;
        if (has_duplicate(keys)) {
          pos_ = start;
          fail_at("duplicate key in the object");
          break;
        }
        return JsonValue::object(std::move(keys), std::move(values));
      }
      fail_at(at_end() ? "unterminated object" : "expected ',' or '}'");
    }
    return JsonValue::null();
  }

  // Sorted indices: n log n however many keys a hostile object has.
  static bool has_duplicate(const std::vector<std::string>& keys) {
    std::vector<size_t> order(keys.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return keys[a] < keys[b]; });
    for (size_t i = 1; i < order.size(); ++i) {
      if (keys[order[i]] == keys[order[i - 1]]) return true;
    }
    return false;
  }

  // The grammar is checked here; from_chars then converts the same span.
  JsonValue parse_number() {
    const size_t start = pos_;
    auto digits = [&] {
      const size_t from = pos_;
      while (!at_end() && peek() >= '0' && peek() <= '9') ++pos_;
      return pos_ - from;
    };
    if (peek() == '-') ++pos_;
    if (peek() == '0') {
      ++pos_;
      if (peek() >= '0' && peek() <= '9') return fail("leading zero in a number");
    } else if (digits() == 0) {
      return fail("expected a digit");
    }
    if (peek() == '.') {
      ++pos_;
      if (digits() == 0) return fail("expected a digit after '.'");
    }
    if (peek() == 'e' || peek() == 'E') {
      ++pos_;
      if (peek() == '+' || peek() == '-') ++pos_;
      if (digits() == 0) return fail("expected a digit in the exponent");
    }
    double value = 0;
    const char* first = text_.data() + start;
    const char* last = text_.data() + pos_;
    const auto [end, error] = std::from_chars(first, last, value);
    if (error == std::errc::result_out_of_range) {
      // from_chars leaves `value` alone when out of range; strtod (the
      // server keeps the "C" locale) tells an underflow, which is a harmless
      // tiny number, from an overflow, which would be an infinity.
      value = std::strtod(std::string(first, last).c_str(), nullptr);
      if (!std::isfinite(value)) {
        pos_ = start;
        return fail("number out of range");
      }
    } else if (error != std::errc() || end != last) {
      pos_ = start;
      return fail("malformed number");
    }
    return JsonValue::number(value);
  }

  static void append_utf8(std::string& out, uint32_t code) {
    if (code < 0x80) {
      out += static_cast<char>(code);
    } else if (code < 0x800) {
      out += static_cast<char>(0xC0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      out += static_cast<char>(0xE0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  // Four hex digits after "\u"; false (and an error) otherwise.
  bool hex4(uint32_t* code) {
    if (text_.size() - pos_ < 4) {
      fail_at("truncated \\u escape");
      return false;
    }
    uint32_t value = 0;
    for (int i = 0; i < 4; ++i) {
      const char c = text_[pos_ + static_cast<size_t>(i)];
      uint32_t digit = 0;
      if (c >= '0' && c <= '9') {
        digit = static_cast<uint32_t>(c - '0');
      } else if (c >= 'a' && c <= 'f') {
        digit = static_cast<uint32_t>(c - 'a' + 10);
      } else if (c >= 'A' && c <= 'F') {
        digit = static_cast<uint32_t>(c - 'A' + 10);
      } else {
        fail_at("bad hex digit in a \\u escape");
        return false;
      }
      value = value * 16 + digit;
    }
    pos_ += 4;
    *code = value;
    return true;
  }

  void parse_escape(std::string& out) {
    const char c = peek();
    ++pos_;
    switch (c) {
      case '"':
        out += '"';
        return;
      case '\\':
        out += '\\';
        return;
      case '/':
        out += '/';
        return;
      case 'b':
        out += '\b';
        return;
      case 'f':
        out += '\f';
        return;
      case 'n':
        out += '\n';
        return;
      case 'r':
        out += '\r';
        return;
      case 't':
        out += '\t';
        return;
      case 'u':
        break;
      default:
        --pos_;
        fail_at(at_end() ? "unterminated string" : "unknown escape");
        return;
    }
    uint32_t code = 0;
    if (!hex4(&code)) return;
    if (code >= 0xDC00 && code <= 0xDFFF) return fail_at("lone low surrogate");
    if (code >= 0xD800 && code <= 0xDBFF) {
      uint32_t low = 0;
      if (!consume_word("\\u")) return fail_at("high surrogate without its low half");
      if (!hex4(&low)) return;
      if (low < 0xDC00 || low > 0xDFFF) return fail_at("high surrogate without its low half");
      code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
    }
    append_utf8(out, code);
  }

  // One UTF-8 sequence copied through; overlong forms, surrogates and code
  // points past U+10FFFF are refused.
  void copy_utf8(std::string& out) {
    const auto lead = static_cast<uint8_t>(text_[pos_]);
    size_t length = 0;
    uint32_t code = 0;
    uint32_t minimum = 0;
    if (lead >= 0xC2 && lead <= 0xDF) {
      length = 2, code = lead & 0x1Fu, minimum = 0x80;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
      length = 3, code = lead & 0x0Fu, minimum = 0x800;
    } else if (lead >= 0xF0 && lead <= 0xF4) {
      length = 4, code = lead & 0x07u, minimum = 0x10000;
    } else {
      return fail_at("invalid UTF-8");
    }
    if (text_.size() - pos_ < length) return fail_at("invalid UTF-8");
    for (size_t i = 1; i < length; ++i) {
      const auto next = static_cast<uint8_t>(text_[pos_ + i]);
      if ((next & 0xC0u) != 0x80u) return fail_at("invalid UTF-8");
      code = (code << 6) | (next & 0x3Fu);
    }
    if (code < minimum || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) {
      return fail_at("invalid UTF-8");
    }
    out.append(text_.substr(pos_, length));
    pos_ += length;
  }

  std::string parse_string() {
    ++pos_;  // the opening quote
    std::string out;
    while (!failed()) {
      if (at_end()) {
        fail_at("unterminated string");
        break;
      }
      const auto c = static_cast<uint8_t>(text_[pos_]);
      if (c == '"') {
        ++pos_;
        return out;
      }
      if (c == '\\') {
        ++pos_;
        parse_escape(out);
      } else if (c < 0x20) {
        fail_at("control character in a string");
      } else if (c < 0x80) {
        out += static_cast<char>(c);
        ++pos_;
      } else {
        copy_utf8(out);
      }
    }
    return {};
  }

  std::string_view text_;
  int max_depth_;
  size_t pos_ = 0;
  Status error_;
};

}  // namespace

Result<JsonValue> parse_json(std::string_view text, const JsonLimits& limits) {
  if (text.size() > limits.max_bytes) {
    return Status::Error(ErrorCode::kCapacity, "JSON: " + std::to_string(text.size()) +
                                                   " bytes, more than the limit of " +
                                                   std::to_string(limits.max_bytes));
  }
  return Parser(text, limits.max_depth).document();
}

}  // namespace rwd::server
