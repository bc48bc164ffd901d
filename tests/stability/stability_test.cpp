// SPDX-License-Identifier: MIT
// Every stability criterion of the scene catalogue, at default settings
// (sleeping on, as a game runs). Piles larger than 1000 boxes run in the
// benchmarks and charts (scripts/charts.sh), not here, for time. The 40-box
// stack runs with the settings rewind-tune recommends for it. The sleep
// scene's asleep_cost_pct is wall time, so it is judged by the benchmarks
// and charts, not here.
#include "scene_criterion.h"

namespace rwd::scenes::test {
namespace {

// A 40-box stack with the settings rewind-tune recommends for it with every
// body awake (`rewind-tune --scene stack --size 40 --no-sleep`; docs/tuning-and-benchmarks.md,
// Tuning): the defaults hold 20 boxes, not 40.
constexpr Tuned kStack40{12, 0};

class Stability : public ::testing::TestWithParam<Criterion> {};

TEST_P(Stability, HoldsAtDefaultSettings) {
  expect_criterion(GetParam());
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, Stability,
    ::testing::Values(
        Criterion{"stack", 5, "drift_m"}, Criterion{"stack", 5, "penetration_mm"},
        Criterion{"stack", 10, "drift_m"}, Criterion{"stack", 10, "penetration_mm"},
        Criterion{"stack", 20, "drift_m"}, Criterion{"stack", 20, "penetration_mm"},
        Criterion{"stack", 40, "drift_m", kStack40},
        Criterion{"stack", 40, "penetration_mm", kStack40}, Criterion{"pyramid", 10, "drift_m"},
        Criterion{"pyramid", 10, "penetration_mm"}, Criterion{"pyramid", 20, "drift_m"},
        Criterion{"pyramid", 20, "penetration_mm"}, Criterion{"pyramid", 30, "drift_m"},
        Criterion{"pyramid", 30, "penetration_mm"}, Criterion{"card_house", 1, "drift_m"},
        Criterion{"card_house", 2, "drift_m"}, Criterion{"card_house", 3, "drift_m"},
        Criterion{"mass_ratio", 10, "drift_m"}, Criterion{"mass_ratio", 10, "penetration_mm"},
        Criterion{"mass_ratio", 100, "drift_m"}, Criterion{"mass_ratio", 100, "penetration_mm"},
        Criterion{"far_stack", 1000, "drift_m"}, Criterion{"far_stack", 1000, "penetration_mm"},
        Criterion{"far_stack", 10000, "drift_m"}, Criterion{"far_stack", 10000, "penetration_mm"},
        Criterion{"kick", 5, "rest_s"}, Criterion{"kick", 5, "drift_m"},
        Criterion{"overlap", 5, "recover_s"}, Criterion{"overlap", 5, "max_speed_mps"},
        Criterion{"overlap", 10, "recover_s"}, Criterion{"overlap", 10, "max_speed_mps"},
        Criterion{"projectile", 50, "tunneled"}, Criterion{"projectile", 200, "tunneled"},
        Criterion{"pile", 250, "escaped"}, Criterion{"pile", 250, "mean_speed_mps"},
        Criterion{"pile", 500, "escaped"}, Criterion{"pile", 500, "mean_speed_mps"},
        Criterion{"pile", 1000, "escaped"}, Criterion{"pile", 1000, "mean_speed_mps"},
        Criterion{"mixed_pile", 250, "escaped"}, Criterion{"mixed_pile", 250, "mean_speed_mps"},
        Criterion{"mixed_pile", 500, "escaped"}, Criterion{"mixed_pile", 500, "mean_speed_mps"},
        Criterion{"convex_pile", 250, "escaped"}, Criterion{"convex_pile", 250, "mean_speed_mps"},
        Criterion{"convex_pile", 500, "escaped"}, Criterion{"convex_pile", 500, "mean_speed_mps"},
        Criterion{"mesh_pile", 250, "escaped"}, Criterion{"mesh_pile", 250, "mean_speed_mps"},
        Criterion{"field_boxes", 25, "drift_m"}, Criterion{"field_boxes", 25, "mean_speed_mps"},
        Criterion{"field_boxes", 100, "drift_m"}, Criterion{"field_boxes", 100, "mean_speed_mps"},
        Criterion{"compound_balance", 4, "tilt_rad"}, Criterion{"compound_pile", 200, "escaped"},
        Criterion{"compound_pile", 200, "mean_speed_mps"}, Criterion{"hull_stack", 5, "drift_m"},
        Criterion{"hull_stack", 5, "penetration_mm"}, Criterion{"hull_stack", 10, "drift_m"},
        Criterion{"hull_stack", 10, "penetration_mm"}, Criterion{"log_cabin", 3, "drift_m"},
        Criterion{"log_cabin", 3, "penetration_mm"}, Criterion{"log_cabin", 6, "drift_m"},
        Criterion{"log_cabin", 6, "penetration_mm"}, Criterion{"crates", 2, "escaped"},
        Criterion{"crates", 8, "escaped"}, Criterion{"crates", 8, "max_speed_mps"},
        Criterion{"crates", 32, "escaped"}, Criterion{"crates", 32, "max_speed_mps"},
        Criterion{"sleep", 10, "sleep_s"}, Criterion{"sleep", 20, "sleep_s"},
        Criterion{"sleep", 30, "sleep_s"}),
    criterion_name);

}  // namespace
}  // namespace rwd::scenes::test
