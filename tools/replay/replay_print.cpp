// SPDX-License-Identifier: MIT
#include "replay_print.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>

namespace rwd::replay_tool {
namespace {

std::string hex64(uint64_t v) {
  char buf[19];
  std::snprintf(buf, sizeof buf, "0x%016" PRIx64, v);
  return buf;
}

// Shortest text that reads back to the same double.
std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string game_label(const replay::VerifyReport& report) {
  if (!report.header) return "";
  return " (game " + report.header->game() + ", " + std::to_string(report.header->player_count()) +
         (report.header->player_count() == 1 ? " player)" : " players)");
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

// JSON has no NaN or infinity; a diverged body can hold them.
std::string json_number(double v) {
  return std::isfinite(v) ? number(v) : "null";
}

template <class T>
std::string json_optional(const std::optional<T>& v) {
  if (!v) return "null";
  if constexpr (std::is_same_v<T, std::string>) {
    return json_string(*v);
  } else {
    return std::to_string(*v);
  }
}

void print_differences(const replay::VerifyReport& report, std::ostream& out) {
  if (report.differences_tick && !report.differences.empty()) {
    out << "fields that differ at tick " << *report.differences_tick
        << " (expected = recorded keyframe, actual = re-simulated):\n";
    for (const sim::FieldDifference& d : report.differences) {
      out << "  body " << d.body_index << " " << d.field << " expected " << number(d.expected)
          << " actual " << number(d.actual) << "\n";
    }
    if (report.differences_total > report.differences.size()) {
      out << "  ... and " << report.differences_total - report.differences.size() << " more\n";
    }
  }
  if (!report.differences_note.empty()) out << "note: " << report.differences_note << "\n";
}

}  // namespace

int verify_exit_code(const replay::VerifyReport& report) {
  if (report.diverged()) return 1;
  if (report.framing_error || report.error) return 2;
  return 0;
}

void print_verify_text(const replay::VerifyReport& report, std::ostream& out) {
  if (report.diverged()) {
    out << "DIVERGED at tick " << *report.first_divergent_tick << ": expected "
        << hex64(report.expected_checksum) << " got " << hex64(report.actual_checksum);
    if (report.divergence_kind == replay::DivergenceKind::kKeyframeState) {
      out << " (keyframe state)";
    }
    out << "\n";
    out << "verified " << report.ticks_verified << " ticks before it" << game_label(report) << "\n";
    print_differences(report, out);
  } else if (report.framing_error || report.error) {
    out << "prefix verified: " << report.ticks_verified << " ticks" << game_label(report);
    if (report.ticks_verified > 0) out << " checksum of last tick " << hex64(report.last_checksum);
    out << "\n";
  } else {
    out << "verified " << report.ticks_verified << " ticks" << game_label(report)
        << " checksum of last tick " << hex64(report.last_checksum) << "\n";
    if (report.keyframes_verified > 0) {
      out << "keyframes matched: " << report.keyframes_verified << "\n";
    }
    if (!report.ended_cleanly) {
      out << "note: no end record; the recording stops on a frame boundary (the server stopped "
             "before finishing the match)\n";
    }
  }
  if (report.framing_error) out << "file breaks at: " << *report.framing_error << "\n";
  if (report.error) out << "cannot verify: " << *report.error << "\n";
}

void print_verify_json(const std::string& file, const replay::VerifyReport& report,
                       std::ostream& out) {
  out << "{\n  \"file\": " << json_string(file) << ",\n";
  if (report.header) {
    out << "  \"game\": " << json_string(report.header->game()) << ",\n"
        << "  \"players\": " << report.header->player_count() << ",\n"
        << "  \"seed\": " << report.header->seed() << ",\n";
  }
  out << "  \"ticks_verified\": " << report.ticks_verified << ",\n"
      << "  \"last_checksum\": " << json_string(hex64(report.last_checksum)) << ",\n"
      << "  \"keyframes_verified\": " << report.keyframes_verified << ",\n"
      << "  \"ended_cleanly\": " << (report.ended_cleanly ? "true" : "false") << ",\n"
      << "  \"diverged\": " << (report.diverged() ? "true" : "false") << ",\n"
      << "  \"first_divergent_tick\": " << json_optional(report.first_divergent_tick) << ",\n";
  if (report.diverged()) {
    out << "  \"divergence_kind\": "
        << (report.divergence_kind == replay::DivergenceKind::kKeyframeState ? "\"keyframe_state\""
                                                                             : "\"tick_checksum\"")
        << ",\n"
        << "  \"expected_checksum\": " << json_string(hex64(report.expected_checksum)) << ",\n"
        << "  \"actual_checksum\": " << json_string(hex64(report.actual_checksum)) << ",\n";
  }
  out << "  \"differences_tick\": " << json_optional(report.differences_tick) << ",\n"
      << "  \"differences_total\": " << report.differences_total << ",\n"
      << "  \"differences\": [";
  for (size_t i = 0; i < report.differences.size(); ++i) {
    const sim::FieldDifference& d = report.differences[i];
    out << (i == 0 ? "\n" : ",\n") << "    {\"body\": " << d.body_index
        << ", \"field\": " << json_string(d.field) << ", \"expected\": " << json_number(d.expected)
        << ", \"actual\": " << json_number(d.actual) << "}";
  }
  out << (report.differences.empty() ? "],\n" : "\n  ],\n")
      << "  \"note\": " << json_string(report.differences_note) << ",\n"
      << "  \"framing_error\": " << json_optional(report.framing_error) << ",\n"
      << "  \"error\": " << json_optional(report.error) << "\n}\n";
}

void print_summary(const std::string& file, const replay::ReplaySummary& s, std::ostream& out) {
  const v1::ReplayHeader& h = s.header;
  out << "replay " << file << "\n"
      << "  format version " << h.format_version() << ", game " << h.game() << ", "
      << h.player_count() << " players, seed " << h.seed() << "\n"
      << "  tick rate " << h.tick_rate_hz() << " Hz, finalization window " << h.window_ticks()
      << " ticks, keyframe interval " << h.keyframe_interval() << " ticks\n"
      << "  server version \"" << h.server_version() << "\", started unix ms "
      << h.started_unix_ms() << "\n";
  if (s.tick_records == 0) {
    out << "ticks: none\n";
  } else {
    out << "ticks: " << s.first_tick << ".." << s.last_tick << " (" << s.tick_records
        << " tick records)\n";
  }
  out << "substituted inputs: " << s.ticks_with_substitutions << " ticks with substitutions\n";
  for (size_t p = 0; p < s.substituted_per_player.size(); ++p) {
    out << "  player " << p << ": " << s.substituted_per_player[p] << "\n";
  }
  uint64_t keyframe_bytes = 0;
  for (const replay::KeyframeInfo& k : s.keyframes) keyframe_bytes += k.state_bytes;
  out << "keyframes: " << s.keyframes.size() << " (" << keyframe_bytes << " bytes)";
  constexpr size_t kListed = 32;
  for (size_t i = 0; i < s.keyframes.size() && i < kListed; ++i) {
    out << (i == 0 ? " after ticks " : " ") << s.keyframes[i].tick;
  }
  if (s.keyframes.size() > kListed) out << " ...";
  out << "\n";
  if (s.end) {
    out << "end: last final tick " << s.end->last_final_tick() << ", reason \"" << s.end->reason()
        << "\"\n";
  } else {
    out << "end: none (the recording stops without an end record)\n";
  }
  out << "valid bytes: " << s.valid_bytes << "\n";
  if (s.error) out << "file breaks at: " << *s.error << "\n";
}

}  // namespace rwd::replay_tool
