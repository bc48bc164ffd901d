// SPDX-License-Identifier: MIT
#include "rewind/replay/replay_verifier.h"
#include "rewind/proto/input_wire.h"

#include <memory>
#include <span>

#include "rewind/game/simulation.h"
#include "rewind/replay/replay_format.h"

namespace rwd::replay {
namespace {

static_assert(kMaxReplayPlayers == game::kMaxPlayers,
              "the replay format and the game layer must agree on the player limit");

using game::Simulation;

std::span<const uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const uint8_t*>(s.data()), s.size()};
}

std::vector<rwd::PlayerInput> inputs_of(const v1::ReplayTick& tick) {
  std::vector<rwd::PlayerInput> inputs;
  inputs.reserve(static_cast<size_t>(tick.inputs_size()));
  // The reader already refused inputs that do not convert.
  for (const v1::Input& in : tick.inputs()) inputs.push_back(*proto::from_wire(in));
  return inputs;
}

void set_differences(VerifyReport& report, const Simulation& recorded, const Simulation& resim,
                     Tick tick, const VerifyOptions& options) {
  std::vector<rwd::BodyField> expected;
  std::vector<rwd::BodyField> actual;
  recorded.dump_bodies(expected);
  resim.dump_bodies(actual);
  std::vector<rwd::FieldDifference> diff = rwd::diff_body_fields(expected, actual);
  report.differences_tick = tick;
  report.differences_total = diff.size();
  if (diff.size() > options.max_differences) diff.resize(options.max_differences);
  report.differences = std::move(diff);
  if (report.differences_total == 0) {
    report.differences_note = "bodies are identical at tick " + std::to_string(tick) +
                              "; the difference is in state the body dump does not show "
                              "(game state, contact or sleep caches)";
  }
}

class Verifier {
 public:
  Verifier(ReplayReader& reader, const VerifyOptions& options, VerifyReport& report)
      : reader_(reader), options_(options), report_(report) {}

  void run() {
    const v1::ReplayHeader& header = reader_.header();
    report_.versions = check_versions(header);
    if (!report_.versions->matches() && !options_.ignore_version) {
      // Stepping another engine's match proves nothing either way; the file
      // is still read so the report says whether it is whole.
      read_rest();
      return;
    }
    setup_.player_count = header.player_count();
    setup_.seed = header.seed();
    Result<std::unique_ptr<Simulation>> sim = Simulation::create(header.game(), setup_);
    if (!sim.ok()) {
      report_.error = "cannot create game \"" + header.game() + "\": " + sim.status().message();
      read_rest();
      return;
    }
    sim_ = std::move(*sim);
    report_.resimulated = true;

    while (std::optional<v1::ReplayRecord> r = read()) {
      const bool go_on = r->has_tick()       ? verify_tick(r->tick())
                         : r->has_keyframe() ? verify_keyframe(r->keyframe())
                                             : true;
      if (!go_on) {
        // After a divergence or an error the rest of the file is only read,
        // not simulated, so the report still says whether it is whole.
        read_rest();
        return;
      }
    }
  }

 private:
  // The next record, or nullopt at the end of the file or when reading
  // stopped (the report then says why).
  std::optional<v1::ReplayRecord> read() {
    if (reader_.state() != ReadState::kReading) return std::nullopt;
    Result<std::optional<v1::ReplayRecord>> record = reader_.next();
    if (!record.ok()) {
      note_stop(record.status());
      return std::nullopt;
    }
    if (record->has_value() && (*record)->has_tick()) ++report_.tick_records;
    return std::move(*record);
  }

  void note_stop(const Status& status) {
    switch (reader_.state()) {
      case ReadState::kTorn:
        report_.torn_frame = status.message();
        break;
      case ReadState::kUnsupported:
        // Without re-simulation the version mismatch already says it.
        if (report_.resimulated) report_.error = status.message();
        break;
      default:
        report_.framing_error = status.message();
        break;
    }
  }

  void read_rest() {
    while (read()) {
    }
  }

  // Steps one recorded tick; false when it diverged or could not run.
  bool verify_tick(const v1::ReplayTick& tick) {
    if (tick.tick() != sim_->tick()) {
      report_.error = "record for tick " + std::to_string(tick.tick()) +
                      " but the simulation is at tick " + std::to_string(sim_->tick());
      return false;
    }
    const std::vector<rwd::PlayerInput> inputs = inputs_of(tick);
    if (Status status = sim_->step(inputs); !status.ok()) {
      report_.error = "the game's rules failed: " + status.message();
      return false;
    }
    const uint64_t actual = sim_->checksum();
    if (actual != tick.checksum()) {
      report_.first_divergent_tick = tick.tick();
      report_.divergence_kind = DivergenceKind::kTickChecksum;
      report_.expected_checksum = tick.checksum();
      report_.actual_checksum = actual;
      if (options_.name_fields) name_fields_after(tick.tick());
      return false;
    }
    ++report_.ticks_verified;
    report_.last_checksum = actual;
    return true;
  }

  // Compares a keyframe with the re-simulated state after the same tick.
  bool verify_keyframe(const v1::ReplayKeyframe& keyframe) {
    Simulation* recorded = load_keyframe(keyframe);
    if (recorded == nullptr) return false;
    const uint64_t expected = recorded->checksum();
    const uint64_t actual = sim_->checksum();
    if (expected != actual) {
      report_.first_divergent_tick = keyframe.tick();
      report_.divergence_kind = DivergenceKind::kKeyframeState;
      report_.expected_checksum = expected;
      report_.actual_checksum = actual;
      set_differences(report_, *recorded, *sim_, keyframe.tick(), options_);
      return false;
    }
    ++report_.keyframes_verified;
    return true;
  }

  // Deserializes a keyframe into the second simulation; nullptr (with
  // report_.error set) when the bytes are refused.
  Simulation* load_keyframe(const v1::ReplayKeyframe& keyframe) {
    const std::string where = "keyframe for tick " + std::to_string(keyframe.tick()) + " (record " +
                              std::to_string(reader_.records_read() - 1) + ")";
    if (!recorded_) {
      Result<std::unique_ptr<Simulation>> sim = Simulation::create(reader_.header().game(), setup_);
      if (!sim.ok()) {
        report_.error = "cannot create game for " + where + ": " + sim.status().message();
        return nullptr;
      }
      recorded_ = std::move(*sim);
    }
    if (Status s = recorded_->deserialize(bytes_of(keyframe.state())); !s.ok()) {
      report_.error = where + " does not load: " + s.message();
      return nullptr;
    }
    // A keyframe holds the state after its tick, so it must be about to
    // simulate the next one.
    if (recorded_->tick() != keyframe.tick() + 1) {
      report_.error = where + " holds the state before tick " + std::to_string(recorded_->tick()) +
                      ", expected before tick " + std::to_string(keyframe.tick() + 1);
      return nullptr;
    }
    return recorded_.get();
  }

  // The checksum after `divergent` disagreed. Only a keyframe has the
  // recorded state, so keep stepping the diverged simulation with the
  // recorded inputs up to the next keyframe and compare the bodies there.
  void name_fields_after(Tick divergent) {
    while (std::optional<v1::ReplayRecord> r = read()) {
      if (r->has_tick()) {
        if (Status status = sim_->step(inputs_of(r->tick())); !status.ok()) {
          report_.differences_note =
              "the game's rules failed after the divergence: " + status.message();
          return;
        }
      } else if (r->has_keyframe()) {
        Simulation* recorded = load_keyframe(r->keyframe());
        if (recorded == nullptr) {
          report_.differences_note = "the keyframe after the divergence does not load";
          return;
        }
        set_differences(report_, *recorded, *sim_, r->keyframe().tick(), options_);
        if (r->keyframe().tick() != divergent && report_.differences_total > 0) {
          report_.differences_note =
              "fields compared at keyframe tick " + std::to_string(r->keyframe().tick()) + ", " +
              std::to_string(r->keyframe().tick() - divergent) + " ticks after the divergence";
        }
        return;
      }
    }
    if (reader_.state() == ReadState::kComplete || reader_.state() == ReadState::kIncomplete) {
      report_.differences_note = "no keyframe at or after tick " + std::to_string(divergent) +
                                 " in the file; the recorded state is known only by its "
                                 "checksum, so fields cannot be named";
    } else {
      report_.differences_note = "no keyframe at or after tick " + std::to_string(divergent) +
                                 " before the file breaks; fields cannot be named";
    }
  }

  ReplayReader& reader_;
  const VerifyOptions& options_;
  VerifyReport& report_;
  game::MatchSetup setup_;
  std::unique_ptr<Simulation> sim_;
  std::unique_ptr<Simulation> recorded_;
};

}  // namespace

VerifyOutcome VerifyReport::outcome() const {
  if (diverged()) return VerifyOutcome::kDiverged;
  if (framing_error || error) return VerifyOutcome::kCorrupt;
  if (version_skipped()) return VerifyOutcome::kVersionMismatch;
  if (!ended_cleanly) return VerifyOutcome::kIncomplete;
  return VerifyOutcome::kVerified;
}

const char* outcome_name(VerifyOutcome outcome) {
  switch (outcome) {
    case VerifyOutcome::kVerified:
      return "verified";
    case VerifyOutcome::kDiverged:
      return "diverged";
    case VerifyOutcome::kCorrupt:
      return "corrupt";
    case VerifyOutcome::kVersionMismatch:
      return "version_mismatch";
    case VerifyOutcome::kIncomplete:
      return "incomplete";
  }
  return "unknown";
}

VerifyReport verify_replay(ReplayReader& reader, const VerifyOptions& options) {
  VerifyReport report;
  report.header = reader.header();
  Verifier(reader, options, report).run();
  report.file_state = reader.state();
  report.ended_cleanly = report.file_state == ReadState::kComplete;
  return report;
}

VerifyReport verify_replay(const std::string& path, const VerifyOptions& options) {
  Result<ReplayReader> reader = ReplayReader::open(path);
  if (!reader.ok()) {
    // Without a whole header there is no game to re-simulate: a file cut
    // inside its first frame is as unverifiable as a damaged one.
    VerifyReport report;
    if (reader.status().code() == ErrorCode::kIo) {
      report.error = reader.status().message();
      report.file_state = ReadState::kIoError;
    } else {
      report.framing_error = reader.status().message();
      report.file_state = ReadState::kCorrupt;
    }
    return report;
  }
  return verify_replay(*reader, options);
}

}  // namespace rwd::replay
