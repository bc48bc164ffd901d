// SPDX-License-Identifier: MIT
#include "rewind/server/http_response.h"

#include <optional>

namespace rwd::server {
namespace {

constexpr std::string_view kCrlf = "\r\n";

Status corrupt(const std::string& what) {
  return Status::Error(ErrorCode::kCorrupt, "HTTP response: " + what);
}

Status too_long(size_t limit) {
  return Status::Error(ErrorCode::kCapacity,
                       "HTTP response: body longer than " + std::to_string(limit) + " bytes");
}

char lower(char c) {
  return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

// RFC 9110 token characters: what a header name is made of.
bool is_token(std::string_view text) {
  if (text.empty()) return false;
  for (const char c : text) {
    const bool alnum = (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
    if (!alnum && std::string_view("!#$%&'*+-.^_`|~").find(c) == std::string_view::npos) {
      return false;
    }
  }
  return true;
}

// Field values and reason phrases: no control characters but tab.
bool is_field_text(std::string_view text) {
  for (const char c : text) {
    if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f) return false;
  }
  return true;
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

// Decimal digits only, at most 18 of them (no overflow, no sign, no spaces).
std::optional<size_t> parse_length(std::string_view text) {
  if (text.empty() || text.size() > 18) return std::nullopt;
  size_t value = 0;
  for (const char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
    value = value * 10 + static_cast<size_t>(c - '0');
  }
  return value;
}

std::optional<size_t> parse_hex_size(std::string_view text) {
  if (text.empty() || text.size() > 15) return std::nullopt;
  size_t value = 0;
  for (const char c : text) {
    size_t digit = 0;
    if (c >= '0' && c <= '9') {
      digit = static_cast<size_t>(c - '0');
    } else if (lower(c) >= 'a' && lower(c) <= 'f') {
      digit = static_cast<size_t>(lower(c) - 'a' + 10);
    } else {
      return std::nullopt;
    }
    value = value * 16 + digit;
  }
  return value;
}

Status parse_status_line(std::string_view line, HttpResponse* out) {
  // "HTTP/1.x SSS reason" or "HTTP/1.x SSS" (the reason may be empty).
  if (line.size() < 12 || line.substr(0, 7) != "HTTP/1." || line[7] < '0' || line[7] > '9' ||
      line[8] != ' ') {
    return corrupt("malformed status line");
  }
  int status = 0;
  for (size_t i = 9; i < 12; ++i) {
    if (line[i] < '0' || line[i] > '9') return corrupt("malformed status code");
    status = status * 10 + (line[i] - '0');
  }
  if (status < 100 || status > 599) return corrupt("status code out of range");
  std::string_view reason;
  if (line.size() > 12) {
    if (line[12] != ' ') return corrupt("malformed status line");
    reason = line.substr(13);
  }
  if (!is_field_text(reason)) return corrupt("control character in the reason phrase");
  out->status = status;
  out->reason = std::string(reason);
  return Status::Ok();
}

// The chunked body starting at `data`; nothing may follow its last CRLF.
Status decode_chunked(std::string_view data, size_t max_body, std::string* body) {
  while (true) {
    const size_t line_end = data.find(kCrlf);
    if (line_end == std::string_view::npos) return corrupt("truncated chunk size line");
    std::string_view size_text = data.substr(0, line_end);
    const size_t extension = size_text.find(';');
    if (extension != std::string_view::npos) {
      if (!is_field_text(size_text.substr(extension))) return corrupt("malformed chunk extension");
      size_text = size_text.substr(0, extension);
    }
    const std::optional<size_t> size = parse_hex_size(trim(size_text));
    if (!size) return corrupt("malformed chunk size");
    data.remove_prefix(line_end + kCrlf.size());
    if (*size == 0) break;
    if (*size > max_body - body->size()) return too_long(max_body);
    if (data.size() < *size + kCrlf.size()) return corrupt("truncated chunk");
    if (data.substr(*size, kCrlf.size()) != kCrlf) return corrupt("chunk not followed by CRLF");
    body->append(data.substr(0, *size));
    data.remove_prefix(*size + kCrlf.size());
  }
  // Trailer fields, then the blank line that ends the message.
  while (true) {
    const size_t line_end = data.find(kCrlf);
    if (line_end == std::string_view::npos) return corrupt("truncated trailer");
    const std::string_view line = data.substr(0, line_end);
    data.remove_prefix(line_end + kCrlf.size());
    if (line.empty()) break;
    const size_t colon = line.find(':');
    if (colon == std::string_view::npos || !is_token(line.substr(0, colon)) ||
        !is_field_text(line.substr(colon + 1))) {
      return corrupt("malformed trailer field");
    }
  }
  if (!data.empty()) return corrupt("data after the chunked body");
  return Status::Ok();
}

}  // namespace

Result<HttpResponse> parse_http_response(std::string_view bytes, size_t max_body_bytes) {
  const size_t head_end = bytes.find("\r\n\r\n");
  if (head_end == std::string_view::npos) return corrupt("no end of the header section");
  std::string_view head = bytes.substr(0, head_end + kCrlf.size());
  std::string_view rest = bytes.substr(head_end + 4);

  HttpResponse response;
  const size_t status_end = head.find(kCrlf);
  if (Status s = parse_status_line(head.substr(0, status_end), &response); !s.ok()) return s;
  head.remove_prefix(status_end + kCrlf.size());

  std::optional<size_t> content_length;
  bool chunked = false;
  while (!head.empty()) {
    const size_t line_end = head.find(kCrlf);
    const std::string_view line = head.substr(0, line_end);
    head.remove_prefix(line_end + kCrlf.size());
    const size_t colon = line.find(':');
    if (colon == std::string_view::npos) return corrupt("header line without ':'");
    const std::string_view name = line.substr(0, colon);
    const std::string_view value = trim(line.substr(colon + 1));
    // A name that starts with a space is an obsolete folded line: refused.
    if (!is_token(name)) return corrupt("malformed header name");
    if (!is_field_text(value)) return corrupt("control character in a header value");
    if (equals_ignoring_case(name, "Content-Length")) {
      const std::optional<size_t> length = parse_length(value);
      if (!length) return corrupt("malformed Content-Length");
      if (content_length && *content_length != *length) {
        return corrupt("conflicting Content-Length headers");
      }
      content_length = length;
    } else if (equals_ignoring_case(name, "Transfer-Encoding")) {
      if (!equals_ignoring_case(value, "chunked")) {
        return corrupt("unsupported Transfer-Encoding '" + std::string(value) + "'");
      }
      chunked = true;
    }
  }
  if (chunked && content_length) return corrupt("both Content-Length and chunked framing");

  // These never carry a body, whatever the headers say.
  const bool bodiless = response.status < 200 || response.status == 204 || response.status == 304;
  if (bodiless) {
    if (!rest.empty()) return corrupt("data after a response that has no body");
  } else if (chunked) {
    if (Status s = decode_chunked(rest, max_body_bytes, &response.body); !s.ok()) return s;
  } else if (content_length) {
    if (*content_length > max_body_bytes) return too_long(max_body_bytes);
    if (rest.size() < *content_length) return corrupt("body shorter than its Content-Length");
    if (rest.size() > *content_length) return corrupt("data after the body");
    response.body = std::string(rest);
  } else {
    if (rest.size() > max_body_bytes) return too_long(max_body_bytes);
    response.body = std::string(rest);
  }
  return response;
}

}  // namespace rwd::server
