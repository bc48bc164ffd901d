// SPDX-License-Identifier: MIT
#include "rewind/tune/game_target.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "rewind/game/game_on.h"
#include "rewind/game/world_lane.h"
#include "rewind/sim/world3d.h"

namespace rwd::tune {
namespace {

// These games run the 3D lane (the 3D world is what is measured here).
const sim::World3D& world3d(const game::Simulation& simulation) {
  return *game::world_of<sim::World3D>(simulation.lane());
}

// The default budget of a game: in 95% of the windows no body ends up more
// than 5 cm from where the reference puts it. 5 cm is a sixteenth of a
// crate and a tenth of a pusher: less than a player notices as a different
// outcome, more than the solver's own resting slop.
constexpr double kPositionBudgetM = 0.05;
constexpr double kWindowPercentile = 0.95;
constexpr Tick kMaxTicks = 36000;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

double magnitude(sim::Vec3 v) {
  return std::sqrt(static_cast<double>(sim::length_squared(v)));
}

// Nearest-rank percentile: the smallest value with at least `p` of the
// values at or below it.
double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<size_t>(std::ceil(p * static_cast<double>(values.size())));
  return values[std::clamp<size_t>(rank, 1, values.size()) - 1];
}

std::string script_name(tools::BotScript script) {
  switch (script) {
    case tools::BotScript::kGame:
      return "game";
    case tools::BotScript::kRandom:
      return "random";
    case tools::BotScript::kCircle:
      return "circle";
    case tools::BotScript::kIdle:
      return "idle";
  }
  return "?";
}

// The reference's saved state, made into the candidate's: its config (as
// the candidate's world holds it: quantized onto the canonical grid, or the
// same setting would not step the same), and the warm-start impulses of the
// contact cache, which are stored per substep (N*s per substep) and so
// scale with the substep length.
void transplant(const game::SimSnapshot& reference, const sim::WorldConfig& config,
                game::SimSnapshot& out) {
  out = reference;
  // The reference is a crates-like game on the 3D lane (create() refused
  // others), so its snapshots hold a WorldState.
  sim::WorldState& world = *game::state_of<sim::World3D>(*out.world);
  const float scale =
      static_cast<float>(world.config.substeps) / static_cast<float>(config.substeps);
  world.config = config;
  for (sim::ContactRecord& record : world.contacts) {
    for (sim::CachedContactPoint& point : record.points) {
      point.normal_impulse *= scale;
      point.tangent_impulse1 *= scale;
      point.tangent_impulse2 *= scale;
    }
  }
}

}  // namespace

Result<std::unique_ptr<GameTarget>> GameTarget::create(const GamePlay& play,
                                                       std::ostream* progress) {
  auto bad = [](const std::string& why) { return Status::Error(ErrorCode::kInvalidArgument, why); };
  std::unique_ptr<game::Game> game = game::make_builtin_game(play.game);
  if (!game) {
    std::string known;
    for (std::string_view n : game::builtin_game_names())
      known += (known.empty() ? "" : ", ") + std::string(n);
    return bad("unknown game '" + play.game + "' (games: " + known + ")");
  }
  const auto* game3d = dynamic_cast<const game::GameOn<sim::World3D>*>(game.get());
  if (game3d == nullptr) return bad("game '" + play.game + "' does not run the 3D lane");
  if (play.players < 1 || play.players > game::kMaxPlayers) {
    return bad("players must be in [1, " + std::to_string(game::kMaxPlayers) + "]");
  }
  if (play.ticks < 1 || play.ticks > kMaxTicks) {
    return bad("ticks must be in [1, " + std::to_string(kMaxTicks) + "]");
  }
  if (play.window_ticks < 1 || play.window_ticks > play.ticks) {
    return bad("the window must be between 1 tick and the match's length");
  }
  if (!(play.diverge_m > 0.0) || !std::isfinite(play.diverge_m)) {
    return bad("the divergence distance must be a positive number of metres");
  }
  std::unique_ptr<GameTarget> target(new GameTarget(play, *game, game3d->world_config()));
  if (Status status = target->play_reference(progress); !status.ok()) return status;
  return target;
}

GameTarget::GameTarget(const GamePlay& play, const game::Game& game, const sim::WorldConfig& config)
    : play_(play), config_(config) {
  inputs_.resize(static_cast<size_t>(play_.ticks));
  for (Tick t = 0; t < play_.ticks; ++t) {
    for (uint32_t p = 0; p < play_.players; ++p) {
      inputs_[t].push_back(tools::bot_input(play_.script, game, play_.seed, p, t));
    }
  }
}

SolverSetting GameTarget::reference_setting() const {
  return {play_.reference_substeps, play_.reference_relax_iterations, config_.contact_hertz};
}

std::string GameTarget::description() const {
  const double tick_s = config_.tick_seconds;
  std::ostringstream out;
  out << "game " << play_.game << ", " << play_.players << " players, seed " << play_.seed << ", "
      << script_name(play_.script) << " inputs, " << play_.ticks << " ticks ("
      << play_.ticks * tick_s << " s); error against the same match at "
      << reference_setting().label() << ", over " << play_.window_ticks * tick_s
      << " s windows each started from the reference's state; ms/step is the whole game tick";
  return out.str();
}

Status GameTarget::play_reference(std::ostream* progress) {
  const sim::WorldConfig config = reference_setting().applied_to(config_);
  auto sim = game::Simulation::create(play_.game, {play_.players, play_.seed}, config);
  if (!sim.ok()) return sim.status();
  if (progress != nullptr) {
    *progress << "rewind-tune: playing the reference match (" << reference_setting().label() << ", "
              << play_.ticks << " ticks)\n";
    progress->flush();
  }
  std::vector<sim::BodyId> ids;
  world3d(**sim).body_ids(ids);
  for (sim::BodyId id : ids) {
    if (world3d(**sim).kind(id) == sim::BodyKind::kDynamic) bodies_.push_back(id);
  }
  const size_t n = bodies_.size();
  reference_position_.resize(static_cast<size_t>(play_.ticks) * n);
  reference_velocity_.resize(reference_position_.size());
  for (Tick t = 0; t < play_.ticks; ++t) {
    if (t % play_.window_ticks == 0) {
      window_starts_.emplace_back();
      (*sim)->save(window_starts_.back());
    }
    if (Status status = (*sim)->step(inputs_[t]); !status.ok()) return status;
    for (size_t b = 0; b < n; ++b) {
      reference_position_[t * n + b] = world3d(**sim).position(bodies_[b]);
      reference_velocity_[t * n + b] = world3d(**sim).linear_velocity(bodies_[b]);
    }
  }
  return Status::Ok();
}

void GameTarget::compare(const game::Simulation& sim, Tick tick, double& position_m,
                         double& velocity_mps, double* position_sum_m) const {
  const size_t n = bodies_.size();
  position_m = 0.0;
  velocity_mps = 0.0;
  for (size_t b = 0; b < n; ++b) {
    const double dp =
        magnitude(world3d(sim).position(bodies_[b]) - reference_position_[tick * n + b]);
    const double dv =
        magnitude(world3d(sim).linear_velocity(bodies_[b]) - reference_velocity_[tick * n + b]);
    // NaN never compares greater: count it as infinitely far.
    position_m = std::isnan(dp) ? kInfinity : std::max(position_m, dp);
    velocity_mps = std::isnan(dv) ? kInfinity : std::max(velocity_mps, dv);
    if (position_sum_m != nullptr) *position_sum_m += dp;
  }
}

Measurement GameTarget::measure(const SolverSetting& setting) {
  Measurement m;
  const sim::WorldConfig config = setting.applied_to(config_);
  if (const auto s = sim::World3D::validate_config(config); !s.ok()) {
    m.error = "refused: " + s.message();
    return m;
  }
  const game::MatchSetup setup{play_.players, play_.seed};
  auto windowed = game::Simulation::create(play_.game, setup, config);
  auto free_run = game::Simulation::create(play_.game, setup, config);
  if (!windowed.ok() || !free_run.ok()) {
    m.error = (windowed.ok() ? free_run.status() : windowed.status()).message();
    return m;
  }

  // The windows, each from the reference's state at its start.
  using Clock = std::chrono::steady_clock;
  Clock::duration stepping{};
  std::vector<double> window_position_m;
  std::vector<double> window_velocity_mps;
  double end_sum_m = 0.0;
  size_t end_samples = 0;
  game::SimSnapshot start;
  const sim::WorldConfig world_config = world3d(**windowed).config();
  for (size_t w = 0; w < window_starts_.size(); ++w) {
    transplant(window_starts_[w], world_config, start);
    (*windowed)->restore(start);
    const Tick first = static_cast<Tick>(w) * play_.window_ticks;
    const Tick end = std::min(play_.ticks, first + play_.window_ticks);
    double worst_p = 0.0;
    double worst_v = 0.0;
    for (Tick t = first; t < end; ++t) {
      const Clock::time_point before = Clock::now();
      if (Status status = (*windowed)->step(inputs_[t]); !status.ok()) {
        m.error = status.message();
        return m;
      }
      stepping += Clock::now() - before;
      double p = 0.0;
      double v = 0.0;
      compare(**windowed, t, p, v, t + 1 == end ? &end_sum_m : nullptr);
      worst_p = std::max(worst_p, p);
      worst_v = std::max(worst_v, v);
    }
    end_samples += bodies_.size();
    window_position_m.push_back(worst_p);
    window_velocity_mps.push_back(worst_v);
  }
  m.ms_per_step = std::chrono::duration<double, std::milli>(stepping).count() / play_.ticks;

  // The free run, until it leaves the reference.
  const double tick_s = config_.tick_seconds;
  double diverged_s = play_.ticks * tick_s;
  for (Tick t = 0; t < play_.ticks; ++t) {
    if (Status status = (*free_run)->step(inputs_[t]); !status.ok()) {
      m.error = status.message();
      return m;
    }
    double p = 0.0;
    double v = 0.0;
    compare(**free_run, t, p, v, nullptr);
    if (p > play_.diverge_m) {
      diverged_s = (t + 1) * tick_s;
      break;
    }
  }

  std::ostringstream window;
  window << play_.window_ticks * tick_s << " s";
  std::ostringstream diverge;
  diverge << play_.diverge_m << " m";
  const double kNoLimit = kInfinity;
  m.metrics = {
      {"position_error_m", "m", percentile(window_position_m, kWindowPercentile),
       scenes::Metric::Bound::kAtMost, kPositionBudgetM,
       "95th percentile over the " + window.str() +
           " windows of the largest body-centre distance from the reference within a window"},
      {"position_error_mean_m", "m", end_samples ? end_sum_m / end_samples : 0.0,
       scenes::Metric::Bound::kAtMost, kNoLimit,
       "mean body-centre distance from the reference at the end of a " + window.str() + " window"},
      {"velocity_error_mps", "m/s", percentile(window_velocity_mps, kWindowPercentile),
       scenes::Metric::Bound::kAtMost, kNoLimit,
       "95th percentile over the " + window.str() +
           " windows of the largest body velocity error within a window"},
      {"diverged_s", "s", diverged_s, scenes::Metric::Bound::kAtLeast, -kNoLimit,
       "seconds a match played from the start without corrections stays within " + diverge.str() +
           " of the reference (the match's length if it never leaves)"},
  };
  return m;
}

}  // namespace rwd::tune
