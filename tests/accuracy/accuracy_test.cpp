// SPDX-License-Identifier: MIT
// Every accuracy criterion of the scene catalogue (analytic answers), at
// default settings.
#include "scene_criterion.h"

namespace rwd::scenes::test {
namespace {

class Accuracy : public ::testing::TestWithParam<Criterion> {};

TEST_P(Accuracy, HoldsAtDefaultSettings) {
  expect_criterion(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Scenes, Accuracy,
                         ::testing::Values(Criterion{"free_fall", 1, "drop_error_pct"},
                                           Criterion{"free_fall", 3, "drop_error_pct"},
                                           Criterion{"bounce", 50, "apex_error_pct"},
                                           Criterion{"bounce", 90, "apex_error_pct"},
                                           Criterion{"slide", 2, "stop_error_pct"},
                                           Criterion{"slide", 5, "stop_error_pct"},
                                           Criterion{"incline_stick", 20, "creep_mm"},
                                           Criterion{"incline_slip", 30, "travel_error_pct"},
                                           Criterion{"hull_slip", 30, "travel_error_pct"},
                                           Criterion{"roll_stop", 1, "stop_error_pct"},
                                           Criterion{"roll_stop", 3, "stop_error_pct"},
                                           Criterion{"roll", 30, "travel_error_pct"},
                                           Criterion{"free_spin", 10, "flip_min_dot"},
                                           Criterion{"free_spin", 10, "momentum_drift_pct"},
                                           Criterion{"free_spin", 10, "energy_drift_pct"}),
                         criterion_name);

}  // namespace
}  // namespace rwd::scenes::test
