// SPDX-License-Identifier: MIT
#pragma once
// The solver settings rewind-tune varies, and the grid it sweeps them over.
// Every other WorldConfig field (gravity, tick length, bounds, sleeping)
// stays as the scene or game set it.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/sim/world_config.h"

namespace rwd::tune {

/// One point of the grid: the three WorldConfig fields that trade accuracy
/// for time.
struct SolverSetting {
  int32_t substeps = 4;          ///< TGS-Soft substeps per tick, [1, 64]
  int32_t relax_iterations = 1;  ///< rigid relax passes per substep, [0, 16]
  float contact_hertz = 30.0f;   ///< contact softness stiffness, Hz, [0.001, 10000]

  /// The setting `config` runs with.
  static SolverSetting of(const sim::WorldConfig& config);
  /// `base` with this setting's three fields in place of its own.
  sim::WorldConfig applied_to(sim::WorldConfig base) const;
  /// "substeps=4 relax=1 hertz=30", the spelling RewindEngine::settings()
  /// and rewind-scene-sweep's CSV use.
  std::string label() const;
  /// Relative work per tick, for ordering only: one solve pass and
  /// relax_iterations relax passes per substep.
  int32_t work() const { return substeps * (1 + relax_iterations); }

  friend bool operator==(const SolverSetting&, const SolverSetting&) = default;
};

/// The values swept for each field; the grid is every combination.
struct SettingGrid {
  std::vector<int32_t> substeps;
  std::vector<int32_t> relax_iterations;
  std::vector<float> contact_hertz;

  /// substeps 4 5 6 8 12 16, relax 0 1 2 4, hertz 15 30 60 120: 96
  /// settings, from cheaper than the default (no relax pass) to four times
  /// its substeps. Fewer than 4 substeps of a 60 Hz tick are refused.
  static SettingGrid standard();
  /// substeps 4 6 8, relax 0 1, hertz 30: 6 settings, for smoke tests.
  static SettingGrid quick();

  /// Every combination without repeats, least work() first (then fewer
  /// substeps, fewer relax passes, lower hertz), so a long sweep reports
  /// the cheap settings first.
  std::vector<SolverSetting> settings() const;
};

/// Parses a comma-separated list of integers in [min, max], e.g. "1,2,4".
/// kInvalidArgument names the item that is not one.
Result<std::vector<int32_t>> parse_int_list(std::string_view text, int32_t min, int32_t max);
/// Parses a comma-separated list of contact stiffnesses in Hz, each in
/// [0.001, 10000] (what World3D accepts), e.g. "15,30".
Result<std::vector<float>> parse_hertz_list(std::string_view text);

}  // namespace rwd::tune
