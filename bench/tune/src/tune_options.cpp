// SPDX-License-Identifier: MIT
#include "rewind/tune/tune_options.h"

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <string_view>

#include "rewind/cli/flag_parser.h"
#include "rewind/game/simulation.h"
#include "rewind/scenes/scene.h"

namespace rwd::tune {
namespace {

constexpr const char* kUsage =
    "rewind-tune (--scene NAME [--size N] | --game NAME [game flags]) [--budget METRIC=LIMIT]...\n"
    "                   [--quick | --substeps LIST --relax LIST --hertz LIST] [--csv PATH]\n"
    "                   [--chart PATH.svg] [--json] | --list";

constexpr const char* kDescription =
    "Finds the cheapest Rewind solver settings (substeps, relax_iterations,\n"
    "contact_hertz) at which a built-in scene or game still meets an error\n"
    "budget: \"model no more than a scene needs\". Runs the target once at\n"
    "every setting of a grid, keeps the settings whose every metric meets its\n"
    "limit, times the cheapest --finalists of those and the default again\n"
    "(round-robin, --repeats runs each) and picks the lowest median ms/step. Progress goes to\n"
    "stderr, the report to stdout.";

constexpr const char* kDetails = R"(
grid:
  The standard grid is substeps 4 5 6 8 12 16 x relax 0 1 2 4 x hertz
  15 30 60 120 (96 settings), run from the least work per tick to the most;
  --quick uses substeps 4 6 8 x relax 0 1 x hertz 30 (6 settings). --substeps,
  --relax and --hertz replace one axis each with a comma-separated list
  (substeps in [1, 64], relax in [0, 16], hertz in [0.001, 10000]). The
  default setting is measured in any case, as the baseline. A setting the
  world refuses (a substep longer than 1/240 s: under 4 at 60 Hz ticks)
  is reported as refused and never picked.

scenes (--scene):
  The scene runs on Rewind with WorldConfig defaults (sleeping on; off with
  --no-sleep) and the setting applied. Its metrics and their limits are the scene's own criteria
  (the ones in docs/BENCHMARKS.md, in the units the scene names); ms/step is
  the wall time of the world's step alone, averaged over the scene's ticks.
  --size picks the scene's size (boxes, base width, ratio...; see --list);
  without it, the size the benchmark charts sweep.

games (--game):
  A game has no analytic answer, so its error is the distance from a
  reference: the same match (--players, --seed, --script inputs for every
  player, --ticks long) played at --reference-substeps/--reference-relax and
  the game's own contact_hertz. Two runs that differ at all drift apart
  chaotically once bodies collide (a crate tips the other way, a jump is
  refused a tick later), so the distance over a whole match measures chaos,
  not the setting. The match is therefore cut into windows of --window-ticks
  (default a quarter second: about one push or landing); each window starts
  the candidate from the reference's own state at its first tick (contact
  warm-start impulses rescaled to the candidate's substep) and plays that
  window's inputs. Longer windows let chaos back in and flatten the
  differences between settings. Metrics:
    position_error_m       95th percentile over the windows of the largest
                           body-centre distance from the reference within a
                           window, m; budget at most 0.05 m unless set
    position_error_mean_m  mean body-centre distance at a window's end, m
    velocity_error_mps     95th percentile over the windows of the largest
                           velocity error within a window, m/s (a jump
                           made a tick earlier or later counts in full)
    diverged_s             seconds a match played from the start without
                           corrections stays within --diverge-m of the
                           reference (the match's length if it never leaves);
                           an "at least" metric
  Only position_error_m has a limit unless --budget sets others. ms/step is
  the whole game tick (inputs, world step, rules) over the windows.

budget:
  --budget METRIC=LIMIT replaces one metric's limit, in the metric's unit and
  with its direction (at most / at least), e.g. --budget penetration_mm=2 or
  --budget position_error_m=0.02. Repeat it for several metrics. A name the
  target does not measure is refused with the list of its metrics.

output:
  The report names the pick with its median ms/step, the default setting's
  cost and whether it meets the budget, the ratio of the two (and whether
  their timed runs overlap, which puts the difference within the machine's
  noise), every metric at the pick, and the WorldConfig fields to set. If no
  setting passes it names the closest one (smallest relative excess over a
  limit). --json prints the same facts as one JSON object instead. --csv
  writes every setting's metrics (columns kind,name,size,settings,substeps,
  relax,hertz,ms_per_step,timing_runs,metric,unit,value,bound,limit,budget,
  pass,setting_pass,default,pick,criterion). --chart draws error against
  ms/step, one panel per metric, with the budget line, the default and the
  pick, as SVG through gnuplot (scripts/setup.sh installs gnuplot-nox).

  Times are wall-clock on a possibly shared machine: compare them within one
  run only. Errors are deterministic: the same setting gives the same values.

exit status:
  0  a setting of the grid meets the budget (the pick is printed)
  1  no setting meets it (the closest is printed)
  2  usage: bad flags or values, an unknown scene, game or metric, an output
     file that cannot be written, gnuplot missing for --chart
  3  the sweep ran but the CSV or the chart could not be written

examples:
  rewind-tune --scene stack --size 10
  rewind-tune --scene pyramid --budget drift_m=0.05 --chart pyramid.svg
  rewind-tune --game crates --players 4 --budget position_error_m=0.02 --csv crates.csv
)";

// The flags as FlagParser fills them, before they are checked together.
struct RawFlags {
  std::string scene;
  int64_t size = 0;
  std::string game;
  int64_t players = 4;
  int64_t seed = 1;
  std::string script = "random";
  int64_t ticks = 1800;
  int64_t window_ticks = 15;
  int64_t reference_substeps = 32;
  int64_t reference_relax = 4;
  double diverge_m = 0.1;
  std::vector<std::string> budgets;
  bool quick = false;
  std::string substeps;
  std::string relax;
  std::string hertz;
  int64_t finalists = 5;
  int64_t repeats = 5;
  std::string csv;
  std::string chart;
  bool json = false;
  bool quiet = false;
  bool no_sleep = false;
  bool list = false;
};

cli::FlagParser declare(RawFlags& f) {
  cli::FlagParser flags("rewind-tune", kUsage, kDescription);
  flags.add_string("scene", &f.scene, "catalogue scene to tune (see --list)");
  flags.add_int("size", &f.size, 0, 1000000, "scene size; 0: the size the charts sweep");
  flags.add_bool("no-sleep", &f.no_sleep,
                 "scene: keep every body awake (what the solver alone must hold)");
  flags.add_string("game", &f.game, "built-in game to tune (see --list)");
  flags.add_int("players", &f.players, 1, game::kMaxPlayers, "game: players in the match");
  flags.add_int("seed", &f.seed, 0, INT64_MAX, "game: match seed and input-script seed");
  flags.add_string("script", &f.script,
                   "game: every player's inputs: game (its own bots), random, circle or idle");
  flags.add_int("ticks", &f.ticks, 1, 36000, "game: match length in ticks (60 per second)");
  flags.add_int("window-ticks", &f.window_ticks, 1, 36000,
                "game: ticks per error window, each restarted from the reference");
  flags.add_int("reference-substeps", &f.reference_substeps, 1, 64, "game: reference substeps");
  flags.add_int("reference-relax", &f.reference_relax, 0, 16, "game: reference relax iterations");
  flags.add_double("diverge-m", &f.diverge_m, 1e-6, 1e4,
                   "game: distance, m, that ends diverged_s's uncorrected match");
  flags.add_string_list("budget", &f.budgets, "METRIC=LIMIT: replaces one metric's limit");
  flags.add_bool("quick", &f.quick, "small grid: substeps 4,6,8, relax 0,1, hertz 30");
  flags.add_string("substeps", &f.substeps, "substeps to sweep, e.g. 4,8,16 (empty: the grid's)");
  flags.add_string("relax", &f.relax, "relax iterations to sweep, e.g. 0,1 (empty: the grid's)");
  flags.add_string("hertz", &f.hertz,
                   "contact_hertz values to sweep, e.g. 30,60 (empty: the grid's)");
  flags.add_int("finalists", &f.finalists, 1, 50, "cheapest passing settings timed again");
  flags.add_int("repeats", &f.repeats, 1, 50,
                "timed runs of each finalist and the default (median)");
  flags.add_string("csv", &f.csv, "write every setting's metrics as CSV to this file");
  flags.add_string("chart", &f.chart, "draw the error-against-cost chart as SVG to this file");
  flags.add_bool("json", &f.json, "print the result as one JSON object instead of the report");
  flags.add_bool("quiet", &f.quiet, "no progress on stderr");
  flags.add_bool("list", &f.list, "list the scenes and games, then exit");
  return flags;
}

// Whether `--name` appears on the command line, in either spelling.
bool given(int argc, const char* const* argv, std::string_view name) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg.size() < name.size() + 2 || arg.substr(0, 2) != "--") continue;
    if (arg.substr(2, name.size()) != name) continue;
    if (arg.size() == name.size() + 2 || arg[name.size() + 2] == '=') return true;
  }
  return false;
}

Status usage(const std::string& message) {
  return Status::Error(ErrorCode::kInvalidArgument, message);
}

}  // namespace

std::string tune_help_text() {
  RawFlags raw;
  return declare(raw).help_text() + kDetails;
}

std::string tune_list_text() {
  std::ostringstream out;
  out << "scenes (--scene NAME [--size N]; * marks the size used without --size):\n";
  for (const scenes::SceneEntry& e : scenes::scene_catalog()) {
    std::string sizes;
    for (int size : e.sizes) {
      sizes +=
          (sizes.empty() ? "" : " ") + std::to_string(size) + (size == e.chart_size ? "*" : "");
    }
    std::string name(e.name);
    name.resize(std::max<size_t>(name.size(), 14), ' ');
    out << "  " << name << " " << e.description << " [sizes " << sizes << "]\n";
  }
  out << "games (--game NAME):\n";
  for (std::string_view name : game::builtin_game_names()) out << "  " << name << "\n";
  return out.str();
}

Result<TuneCommand> parse_tune_command(int argc, const char* const* argv) {
  RawFlags raw;
  cli::FlagParser flags = declare(raw);
  if (Status status = flags.parse(argc, argv); !status.ok()) return status;
  TuneCommand cmd;
  if (flags.help_requested()) {
    cmd.action = TuneCommand::Action::kHelp;
    return cmd;
  }
  if (raw.list) {
    cmd.action = TuneCommand::Action::kList;
    return cmd;
  }

  if (raw.scene.empty() == raw.game.empty()) {
    return usage("give either --scene NAME or --game NAME (see rewind-tune --list)");
  }
  static constexpr std::string_view kGameFlags[] = {
      "players",         "seed",     "script", "ticks", "window-ticks", "reference-substeps",
      "reference-relax", "diverge-m"};
  if (!raw.scene.empty()) {
    for (std::string_view name : kGameFlags) {
      if (given(argc, argv, name))
        return usage("--" + std::string(name) + " applies to --game only");
    }
  } else if (given(argc, argv, "size")) {
    return usage("--size applies to --scene only (a game's size is --players)");
  } else if (raw.no_sleep) {
    return usage("--no-sleep applies to --scene only");
  }
  if (raw.window_ticks > raw.ticks) {
    return usage("--window-ticks: " + std::to_string(raw.window_ticks) +
                 " is longer than the match (--ticks " + std::to_string(raw.ticks) + ")");
  }
  tools::BotScript script{};
  if (!tools::parse_bot_script(raw.script, &script)) {
    return usage("--script: expected game, random, circle or idle, got '" + raw.script + "'");
  }
  if (raw.quick && (!raw.substeps.empty() || !raw.relax.empty() || !raw.hertz.empty())) {
    return usage("--quick is a grid of its own; give it or --substeps/--relax/--hertz, not both");
  }

  if (!raw.chart.empty() &&
      (raw.chart.size() < 4 || raw.chart.substr(raw.chart.size() - 4) != ".svg")) {
    return usage("--chart: the chart is SVG; give a path ending in .svg, got '" + raw.chart + "'");
  }

  SettingGrid grid = raw.quick ? SettingGrid::quick() : SettingGrid::standard();
  if (!raw.substeps.empty()) {
    auto list = parse_int_list(raw.substeps, 1, 64);
    if (!list.ok()) return usage("--substeps: " + list.status().message());
    grid.substeps = *list;
  }
  if (!raw.relax.empty()) {
    auto list = parse_int_list(raw.relax, 0, 16);
    if (!list.ok()) return usage("--relax: " + list.status().message());
    grid.relax_iterations = *list;
  }
  if (!raw.hertz.empty()) {
    auto list = parse_hertz_list(raw.hertz);
    if (!list.ok()) return usage("--hertz: " + list.status().message());
    grid.contact_hertz = *list;
  }
  for (const std::string& text : raw.budgets) {
    if (Status status = cmd.plan.budget.add(text); !status.ok()) return status;
  }

  cmd.scene = raw.scene;
  cmd.size = static_cast<int>(raw.size);
  cmd.awake = raw.no_sleep;
  cmd.game = raw.game;
  cmd.play.game = raw.game;
  cmd.play.players = static_cast<uint32_t>(raw.players);
  cmd.play.seed = static_cast<uint64_t>(raw.seed);
  cmd.play.script = script;
  cmd.play.ticks = static_cast<Tick>(raw.ticks);
  cmd.play.window_ticks = static_cast<Tick>(raw.window_ticks);
  cmd.play.reference_substeps = static_cast<int32_t>(raw.reference_substeps);
  cmd.play.reference_relax_iterations = static_cast<int32_t>(raw.reference_relax);
  cmd.play.diverge_m = raw.diverge_m;
  cmd.plan.grid = grid.settings();
  cmd.plan.finalists = static_cast<int>(raw.finalists);
  cmd.plan.repeats = static_cast<int>(raw.repeats);
  cmd.csv_path = raw.csv;
  cmd.chart_path = raw.chart;
  cmd.json = raw.json;
  cmd.quiet = raw.quiet;
  return cmd;
}

}  // namespace rwd::tune
