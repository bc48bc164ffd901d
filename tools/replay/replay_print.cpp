// SPDX-License-Identifier: MIT
#include "replay_print.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <span>

#include "rewind/cli/json_text.h"
#include "rewind/replay/engine_identity.h"
#include "rewind/replay/replay_format.h"

namespace rwd::replay_tool {
namespace {

using cli::json_string;

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

std::string json_bool(bool v) {
  return v ? "true" : "false";
}

std::string json_identity(const replay::EngineIdentity& id) {
  return std::string("{\"format_version\": ") + std::to_string(id.format_version) +
         ", \"engine\": " + (id.recorded() ? json_string(id.engine) : "null") +
         ", \"sim_revision\": " + (id.recorded() ? std::to_string(id.sim_revision) : "null") +
         ", \"game\": " + json_string(id.game) +
         ", \"rules_version\": " + json_optional(id.rules_version) +
         ", \"label\": " + json_string(id.label()) + "}";
}

const char* outcome_meaning(replay::VerifyOutcome outcome) {
  switch (outcome) {
    case replay::VerifyOutcome::kVerified:
      return "verified and complete";
    case replay::VerifyOutcome::kDiverged:
      return "diverged: re-simulation disagrees with the recording";
    case replay::VerifyOutcome::kCorrupt:
      return "corrupt or unverifiable";
    case replay::VerifyOutcome::kVersionMismatch:
      return "recorded by another engine revision, rules version or world config: not "
             "re-simulated";
    case replay::VerifyOutcome::kIncomplete:
      return "incomplete: the valid prefix verified, no end record";
  }
  return "";
}

// Ticks are contiguous from 0, so N tick records end after tick N-1.
Tick last_recorded_tick(uint64_t tick_records) {
  return tick_records == 0 ? kNoTick : static_cast<Tick>(tick_records - 1);
}

// The recorded identity against this build's, when they differ.
void print_versions(const replay::VerifyReport& report, std::ostream& out) {
  if (!report.versions || report.versions->matches()) return;
  const replay::VersionCheck& v = *report.versions;
  if (report.resimulated) {
    out << "note: versions differ: replay was recorded by " << v.recorded_label()
        << "; this build runs " << v.this_build.label()
        << "; re-simulating anyway (--ignore-version)\n";
  } else {
    out << "replay was recorded by " << v.recorded_label() << "; this build runs "
        << v.this_build.label() << ": not re-simulated\n";
  }
  for (const std::string& d : v.differences) out << "  " << d << "\n";
}

// The recorded engine and world config, and how this build compares.
void print_identity(const v1::ReplayHeader& h, std::ostream& out) {
  const replay::VersionCheck v = replay::check_versions(h);
  if (v.recorded.recorded()) {
    out << "  engine " << v.recorded_label();
  } else {
    out << "  engine not recorded (replay format " << h.format_version() << ")";
  }
  if (v.matches()) {
    out << "; this build runs the same\n";
  } else {
    out << "; this build runs " << v.this_build.label() << ", which differs:\n";
    for (const std::string& d : v.differences) out << "    " << d << "\n";
  }
  if (!v.recorded.recorded()) {
    out << "world config: not recorded\n";
    return;
  }
  const std::string& bytes = h.world_config();
  auto fields = replay::describe_world_config(
      h.game(),
      std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
  if (!fields.ok()) {
    out << "world config: " << bytes.size() << " bytes this build cannot decode ("
        << fields.status().message() << ")\n";
    return;
  }
  out << "world config:\n";
  for (const auto& [name, value] : *fields) {
    out << "  " << name << " " << value << "\n";
  }
}

void print_differences(const replay::VerifyReport& report, std::ostream& out) {
  if (report.differences_tick && !report.differences.empty()) {
    out << "fields that differ at tick " << *report.differences_tick
        << " (expected = recorded keyframe, actual = re-simulated):\n";
    for (const rwd::FieldDifference& d : report.differences) {
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
  switch (report.outcome()) {
    case replay::VerifyOutcome::kVerified:
      return kExitVerified;
    case replay::VerifyOutcome::kDiverged:
      return kExitDiverged;
    case replay::VerifyOutcome::kCorrupt:
      return kExitCorrupt;
    case replay::VerifyOutcome::kVersionMismatch:
      return kExitVersionMismatch;
    case replay::VerifyOutcome::kIncomplete:
      return kExitIncomplete;
  }
  return kExitCorrupt;
}

int inspect_exit_code(const replay::ReplaySummary& summary) {
  switch (summary.state) {
    case replay::ReadState::kComplete:
      return kExitVerified;
    case replay::ReadState::kIncomplete:
    case replay::ReadState::kTorn:
      return kExitIncomplete;
    case replay::ReadState::kUnsupported:
      return kExitVersionMismatch;
    case replay::ReadState::kReading:
    case replay::ReadState::kCorrupt:
    case replay::ReadState::kIoError:
      break;
  }
  return kExitCorrupt;
}

void print_verify_text(const replay::VerifyReport& report, std::ostream& out) {
  print_versions(report, out);
  if (report.diverged()) {
    out << "DIVERGED at tick " << *report.first_divergent_tick << ": expected "
        << hex64(report.expected_checksum) << " got " << hex64(report.actual_checksum);
    if (report.divergence_kind == replay::DivergenceKind::kKeyframeState) {
      out << " (keyframe state)";
    }
    out << "\n";
    out << "verified " << report.ticks_verified << " ticks before it" << game_label(report) << "\n";
    print_differences(report, out);
  } else if (report.version_skipped()) {
    if (report.file_state == replay::ReadState::kUnsupported) {
      out << "file: records of a newer format, not read\n";
    } else {
      out << "file: " << report.tick_records << " tick records"
          << (report.ended_cleanly ? ", complete" : "") << "\n";
    }
  } else if (report.outcome() == replay::VerifyOutcome::kVerified) {
    out << "verified " << report.ticks_verified << " ticks" << game_label(report)
        << " checksum of last tick " << hex64(report.last_checksum) << "\n";
  } else {
    out << "prefix verified: " << report.ticks_verified << " ticks" << game_label(report);
    if (report.ticks_verified > 0) out << " checksum of last tick " << hex64(report.last_checksum);
    out << "\n";
  }
  if (!report.diverged() && report.keyframes_verified > 0) {
    out << "keyframes matched: " << report.keyframes_verified << "\n";
  }
  if (report.torn_frame) {
    out << "INCOMPLETE: the file ends inside a frame, as a write cut short leaves it: "
        << *report.torn_frame << "\n";
  } else if (report.file_state == replay::ReadState::kIncomplete) {
    out << "INCOMPLETE: no end record; the recording stops "
        << replay::describe_last_tick(last_recorded_tick(report.tick_records))
        << " on a frame boundary (the server stopped before finishing the match)\n";
  }
  if (report.framing_error) out << "file breaks at: " << *report.framing_error << "\n";
  if (report.error) out << "cannot verify: " << *report.error << "\n";
  if (report.outcome() == replay::VerifyOutcome::kVersionMismatch) {
    const replay::EngineIdentity& recorded = report.versions->recorded;
    if (report.file_state == replay::ReadState::kUnsupported) {
      out << "verify it with a build that reads replay format " << recorded.format_version << "\n";
    } else if (!recorded.recorded()) {
      out << "verify it with the build that recorded it, or pass --ignore-version to "
             "re-simulate anyway\n";
    } else {
      out << "verify it with a build that runs " << report.versions->recorded_label()
          << ", or pass --ignore-version to re-simulate anyway\n";
    }
  }
}

void print_verify_json(const std::string& file, const replay::VerifyReport& report,
                       std::ostream& out) {
  const replay::VerifyOutcome outcome = report.outcome();
  out << "{\n  \"file\": " << json_string(file) << ",\n"
      << "  \"outcome\": " << json_string(replay::outcome_name(outcome)) << ",\n"
      << "  \"exit_code\": " << verify_exit_code(report) << ",\n"
      << "  \"meaning\": " << json_string(outcome_meaning(outcome)) << ",\n";
  if (report.header) {
    out << "  \"game\": " << json_string(report.header->game()) << ",\n"
        << "  \"players\": " << report.header->player_count() << ",\n"
        << "  \"seed\": " << report.header->seed() << ",\n";
  }
  if (report.versions) {
    out << "  \"recorded\": " << json_identity(report.versions->recorded) << ",\n"
        << "  \"this_build\": " << json_identity(report.versions->this_build) << ",\n"
        << "  \"versions_match\": " << json_bool(report.versions->matches()) << ",\n"
        << "  \"version_differences\": [";
    const std::vector<std::string>& diffs = report.versions->differences;
    for (size_t i = 0; i < diffs.size(); ++i) {
      out << (i == 0 ? "" : ", ") << json_string(diffs[i]);
    }
    out << "],\n";
  } else {
    out << "  \"recorded\": null,\n  \"this_build\": null,\n  \"versions_match\": null,\n"
        << "  \"version_differences\": [],\n";
  }
  out << "  \"resimulated\": " << json_bool(report.resimulated) << ",\n"
      << "  \"complete\": " << json_bool(report.ended_cleanly) << ",\n"
      << "  \"file_state\": " << json_string(replay::read_state_name(report.file_state)) << ",\n"
      << "  \"tick_records\": " << report.tick_records << ",\n"
      << "  \"ticks_verified\": " << report.ticks_verified << ",\n"
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
    const rwd::FieldDifference& d = report.differences[i];
    out << (i == 0 ? "\n" : ",\n") << "    {\"body\": " << d.body_index
        << ", \"field\": " << json_string(d.field) << ", \"expected\": " << json_number(d.expected)
        << ", \"actual\": " << json_number(d.actual) << "}";
  }
  out << (report.differences.empty() ? "],\n" : "\n  ],\n")
      << "  \"note\": " << json_string(report.differences_note) << ",\n"
      << "  \"torn_frame\": " << json_optional(report.torn_frame) << ",\n"
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
  print_identity(h, out);
  if (s.state == replay::ReadState::kUnsupported) {
    out << "records: not read: " << s.error.value_or("") << "\n";
    return;
  }
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
  switch (s.state) {
    case replay::ReadState::kComplete:
      out << "file: complete\n";
      break;
    case replay::ReadState::kIncomplete:
      out << "file: INCOMPLETE: no end record; the recording stops "
          << replay::describe_last_tick(s.last_tick) << " on a frame boundary\n";
      break;
    case replay::ReadState::kTorn:
      out << "file: INCOMPLETE: the file ends inside a frame, as a write cut short leaves it: "
          << s.error.value_or("") << "\n";
      break;
    case replay::ReadState::kUnsupported:  // returned above
    case replay::ReadState::kReading:
    case replay::ReadState::kCorrupt:
    case replay::ReadState::kIoError:
      out << "file: CORRUPT: breaks at: " << s.error.value_or("") << "\n";
      break;
  }
}

}  // namespace rwd::replay_tool
