// SPDX-License-Identifier: MIT
#include "rewind/server/live_api.h"

#include <charconv>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

namespace rwd::server {
namespace {

using Json = nlohmann::json;

HttpReply bytes_reply(const std::vector<uint8_t>& bytes) {
  HttpReply reply;
  reply.content_type = "application/octet-stream";
  reply.body.assign(bytes.begin(), bytes.end());
  reply.headers.emplace_back("Cache-Control", "no-store");
  return reply;
}

std::string html_escaped(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// The value of `key` in a query string ("a=1&from=20"); nullopt when absent.
std::optional<std::string_view> query_value(std::string_view query, std::string_view key) {
  while (!query.empty()) {
    const size_t amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    const size_t eq = pair.find('=');
    if (pair.substr(0, eq) == key) {
      return eq == std::string_view::npos ? std::string_view() : pair.substr(eq + 1);
    }
    if (amp == std::string_view::npos) break;
    query.remove_prefix(amp + 1);
  }
  return std::nullopt;
}

std::string names_text(const LiveFeed::Summary& s) {
  std::string text;
  for (size_t p = 0; p < s.player_names.size(); ++p) {
    if (p > 0) text += ", ";
    text += s.player_names[p].empty() ? "(free)" : s.player_names[p];
  }
  return text;
}

}  // namespace

LiveApi::LiveApi(FindFn find, ListFn list, std::optional<StaticFiles> viewer)
    : find_(std::move(find)), list_(std::move(list)), viewer_(std::move(viewer)) {}

HttpReply LiveApi::handle(const HttpRequest& request) const {
  last_request_.store(std::chrono::steady_clock::now().time_since_epoch().count(),
                      std::memory_order_relaxed);
  if (request.method != "GET" && request.method != "HEAD") return method_not_allowed();
  const std::string_view path = request.path();
  if (path == "/") {
    const bool watching = query_value(request.query(), "live").has_value();
    if (watching && viewer_) return *viewer_->find("/index.html");
    return listing_page();
  }
  if (path == "/live/matches") return listing_json();
  constexpr std::string_view kMatchPrefix = "/live/";
  if (path.substr(0, kMatchPrefix.size()) == kMatchPrefix) {
    return match_route(path.substr(kMatchPrefix.size()), request.query());
  }
  if (viewer_) {
    if (auto file = viewer_->find(path)) return *file;
  }
  return text_reply(404, "not found\n");
}

HttpReply LiveApi::listing_page() const {
  std::string html =
      "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
      "<title>Rewind: live matches</title><link rel=\"icon\" href=\"data:,\"></head>\n"
      "<body><h1>Live matches</h1>\n";
  const auto feeds = list_();
  if (feeds.empty()) html += "<p>No match is live.</p>\n";
  if (!viewer_) {
    html +=
        "<p>This server has no viewer files (rewind-server --live-viewer-dir DIR): the "
        "data is at /live/matches.</p>\n";
  }
  html += "<ul>\n";
  for (const auto& feed : feeds) {
    const LiveFeed::Summary s = feed->summary();
    const std::string id = html_escaped(s.match_id);
    html += "<li>";
    html += viewer_ ? "<a href=\"/?live=" + id + "\">" + id + "</a>" : id;
    html += " · " + html_escaped(s.game) + " · " + html_escaped(names_text(s)) + " · tick " +
            std::to_string(s.newest_final) + (s.ended ? " · ended" : "") + "</li>\n";
  }
  html += "</ul></body></html>\n";
  HttpReply reply;
  reply.content_type = "text/html; charset=utf-8";
  reply.body = std::move(html);
  reply.headers.emplace_back("Cache-Control", "no-store");
  return reply;
}

HttpReply LiveApi::listing_json() const {
  Json list = Json::array();
  for (const auto& feed : list_()) {
    const LiveFeed::Summary s = feed->summary();
    list.push_back({{"match", s.match_id},
                    {"game", s.game},
                    {"players", s.players},
                    {"names", s.player_names},
                    {"final_tick", s.newest_final},
                    {"visible_tick", s.published},
                    {"tick_rate", s.tick_rate_hz},
                    {"ended", s.ended}});
  }
  HttpReply reply;
  // Names are whatever clients sent: invalid UTF-8 is replaced, not thrown.
  reply.body = list.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
  reply.headers.emplace_back("Cache-Control", "no-store");
  return reply;
}

HttpReply LiveApi::match_route(std::string_view rest, std::string_view query) const {
  const size_t slash = rest.find('/');
  if (slash == std::string_view::npos) return text_reply(404, "not found\n");
  const std::string_view id = rest.substr(0, slash);
  const std::string_view what = rest.substr(slash + 1);
  if (what != "start" && what != "ticks") return text_reply(404, "not found\n");
  const std::shared_ptr<const LiveFeed> feed = find_(id);
  if (!feed) {
    return text_reply(
        404, "no live match '" + std::string(id.substr(0, 64)) + "' (unknown, or not live)\n");
  }
  std::vector<uint8_t> bytes;
  if (what == "start") {
    if (Status s = feed->start_bundle(bytes); !s.ok()) return text_reply(503, s.message() + "\n");
    return bytes_reply(bytes);
  }
  const std::optional<std::string_view> from_text = query_value(query, "from");
  Tick from = 0;
  const char* end = from_text ? from_text->data() + from_text->size() : nullptr;
  if (!from_text || from_text->empty() ||
      std::from_chars(from_text->data(), end, from).ptr != end || from < 0) {
    return text_reply(400, "ticks needs from=T, a tick >= 0\n");
  }
  if (Status s = feed->ticks_from(from, bytes); !s.ok()) {
    return text_reply(s.code() == ErrorCode::kNotFound ? 410 : 400, s.message() + "\n");
  }
  return bytes_reply(bytes);
}

}  // namespace rwd::server
