// SPDX-License-Identifier: MIT
#include "rewind/game/sync_test.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <utility>

#include "rewind/core/splitmix64.h"
#include "rewind/game/simulation.h"

namespace rwd::game {
namespace {

constexpr size_t kMaxFieldsReported = 16;

/// The default inputs: each player holds a random input for 1 to 6 ticks,
/// from one seeded SplitMix64 stream: axes and 4 buttons for the stick
/// input, every field within its range for a game's own.
class ScriptedInputs {
 public:
  ScriptedInputs(const InputSpec& spec, uint32_t players, uint64_t seed)
      : spec_(spec), rng_{seed}, held_(players), hold_(players, 0) {}

  void fill(std::span<PlayerInput> out) {
    for (size_t p = 0; p < out.size(); ++p) {
      if (hold_[p] == 0) {
        if (&spec_ == &stick_input_spec()) {
          StickInput stick;
          stick.axis_x = static_cast<int16_t>(static_cast<int32_t>(rng_.below(2001)) - 1000);
          stick.axis_y = static_cast<int16_t>(static_cast<int32_t>(rng_.below(2001)) - 1000);
          stick.buttons = static_cast<uint32_t>(rng_.next() & 0xFu);
          held_[p] = PlayerInput::of(stick);
        } else {
          held_[p] = random_input(spec_, rng_.next());
        }
        hold_[p] = static_cast<uint32_t>(1 + rng_.below(6));
      }
      --hold_[p];
      out[p] = held_[p];
    }
  }

 private:
  const InputSpec& spec_;
  SplitMix64 rng_;
  std::vector<PlayerInput> held_;
  std::vector<uint32_t> hold_;
};

/// What differs between the first run's state (`expected`) and a check's.
SyncTestFailure compare(SyncCheck check, Tick tick, const Simulation& expected,
                        const Simulation& actual) {
  SyncTestFailure f;
  f.check = check;
  f.tick = tick;
  f.expected = expected.checksum();
  f.actual = actual.checksum();
  std::vector<rwd::BodyField> want;
  std::vector<rwd::BodyField> got;
  expected.dump_bodies(want);
  actual.dump_bodies(got);
  f.fields = rwd::diff_body_fields(want, got);
  if (f.fields.size() > kMaxFieldsReported) f.fields.resize(kMaxFieldsReported);
  const std::span<const std::byte> a = expected.game_state();
  const std::span<const std::byte> b = actual.game_state();
  const size_t common = std::min(a.size(), b.size());
  const auto mismatch =
      std::mismatch(a.begin(), a.begin() + static_cast<ptrdiff_t>(common), b.begin());
  if (mismatch.first != a.begin() + static_cast<ptrdiff_t>(common) || a.size() != b.size()) {
    f.game_state_byte = static_cast<size_t>(mismatch.first - a.begin());
  }
  return f;
}

Status invalid(const std::string& message) {
  return Status::Error(ErrorCode::kInvalidArgument, "sync test: " + message);
}

}  // namespace

const char* sync_check_name(SyncCheck check) {
  switch (check) {
    case SyncCheck::kRollback:
      return "rollback";
    case SyncCheck::kRoundTrip:
      return "round trip";
    case SyncCheck::kSecondInstance:
      return "second instance";
  }
  return "?";
}

std::string SyncTestFailure::describe() const {
  char head[160];
  std::snprintf(head, sizeof head,
                "%s check after tick %d: checksum %016" PRIx64 " expected %016" PRIx64,
                sync_check_name(check), tick, actual, expected);
  std::string text = head;
  if (!fields.empty()) {
    const rwd::FieldDifference& d = fields.front();
    char field[200];
    std::snprintf(field, sizeof field, "; first field: body %u %s = %.9g, expected %.9g",
                  d.body_index, d.field.c_str(), d.actual, d.expected);
    text += field;
  }
  if (game_state_byte) text += "; game state differs from byte " + std::to_string(*game_state_byte);
  if (fields.empty() && !game_state_byte) {
    text += "; no body field or state byte differs: a hashed value the dump does not show";
  }
  return text;
}

Result<SyncTestReport> run_sync_test(std::string_view game_name, const MatchSetup& setup,
                                     const SyncTestOptions& options, const SyncTestInputs& inputs) {
  if (options.ticks < 1 || options.ticks > 1'000'000) return invalid("ticks out of [1, 1000000]");
  if (options.check_distance < 1 || options.check_distance > 64) {
    return invalid("check distance out of [1, 64]");
  }
  auto first = Simulation::create(game_name, setup);
  if (!first.ok()) return first.status();
  Simulation& sim = **first;
  std::unique_ptr<Simulation> twin;
  if (options.second_instance) {
    auto made = Simulation::create(game_name, setup);
    if (!made.ok()) return made.status();
    twin = std::move(*made);
  }
  auto scratch_made = Simulation::create(game_name, setup);
  if (!scratch_made.ok()) return scratch_made.status();
  Simulation& scratch = **scratch_made;  // reloads and expected states for diffs

  const uint32_t players = setup.player_count;
  const size_t ring = options.check_distance + 1;
  // The first run's states at positions t - distance .. t, its inputs and
  // checksums, by position modulo the ring.
  std::vector<SimSnapshot> states(ring);
  std::vector<std::vector<PlayerInput>> ring_inputs(ring, std::vector<PlayerInput>(players));
  std::vector<uint64_t> checksums(ring + 1, 0);
  SimSnapshot after;  // the first run's state after the present tick
  ScriptedInputs scripted(scratch.game().input_spec(), players, options.input_seed);
  std::vector<uint8_t> bytes;
  std::unique_ptr<Simulation> reloaded;  // a round trip waiting to step the next tick

  SyncTestReport report;
  for (Tick t = 0; t < static_cast<Tick>(options.ticks); ++t) {
    const size_t slot = static_cast<size_t>(t) % ring;
    std::span<PlayerInput> in(ring_inputs[slot]);
    if (inputs) {
      inputs(t, in);
    } else {
      scripted.fill(in);
    }
    sim.save(states[slot]);
    // The rules' own errors end the test with their message: they are not
    // a determinism failure, but nothing after them can be checked.
    if (Status status = sim.step(in); !status.ok()) return status;
    const uint64_t checksum = sim.checksum();
    checksums[static_cast<size_t>(t + 1) % (ring + 1)] = checksum;
    report.ticks = static_cast<uint32_t>(t + 1);
    report.final_checksum = checksum;

    if (twin) {
      if (Status status = twin->step(in); !status.ok()) return status;
      if (twin->checksum() != checksum) {
        report.failure = compare(SyncCheck::kSecondInstance, t, sim, *twin);
        return report;
      }
    }
    if (reloaded) {
      // The reloaded state steps this tick as the first run did.
      if (Status status = reloaded->step(in); !status.ok()) return status;
      if (reloaded->checksum() != checksum) {
        report.failure = compare(SyncCheck::kRoundTrip, t, sim, *reloaded);
        return report;
      }
      reloaded.reset();
    }

    // Roll back and re-simulate the last ticks; the re-simulated state is
    // the one that goes on, as in a rollback session.
    sim.save(after);
    const Tick from = std::max<Tick>(0, t + 1 - static_cast<Tick>(options.check_distance));
    sim.restore(states[static_cast<size_t>(from) % ring]);
    for (Tick u = from; u <= t; ++u) {
      if (Status status = sim.step(ring_inputs[static_cast<size_t>(u) % ring]); !status.ok()) {
        return status;
      }
      ++report.resimulated_ticks;
      if (sim.checksum() != checksums[static_cast<size_t>(u + 1) % (ring + 1)]) {
        scratch.restore(u == t ? after : states[static_cast<size_t>(u + 1) % ring]);
        report.failure = compare(SyncCheck::kRollback, u, scratch, sim);
        return report;
      }
    }

    if (options.round_trip_every > 0 && (t + 1) % options.round_trip_every == 0 &&
        t + 1 < static_cast<Tick>(options.ticks)) {
      sim.serialize(bytes);
      auto fresh = Simulation::create(game_name, setup);
      if (!fresh.ok()) return fresh.status();
      if (Status loaded = (*fresh)->deserialize(bytes); !loaded.ok()) {
        return Status::Error(ErrorCode::kCorrupt, "sync test: the state after tick " +
                                                      std::to_string(t) +
                                                      " does not load: " + loaded.message());
      }
      ++report.round_trips;
      if ((*fresh)->checksum() != checksum) {
        report.failure = compare(SyncCheck::kRoundTrip, t, sim, **fresh);
        return report;
      }
      reloaded = std::move(*fresh);
    }
  }
  return report;
}

}  // namespace rwd::game
