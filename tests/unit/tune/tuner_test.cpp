// SPDX-License-Identifier: MIT
// The sweep and the pick on a target whose errors and costs are known, the
// budget, and the grid.
#include "rewind/tune/tuner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>

#include "rewind/tune/tune_report.h"

namespace rwd::tune {
namespace {

// Error falls and cost rises with the work per tick; substeps cost more than
// relax passes, so (4, 1) is cheaper than (8, 0). Its default is (8, 1).
class FakeTarget final : public TuneTarget {
 public:
  std::string kind() const override { return "scene"; }
  std::string name() const override { return "fake"; }
  int size() const override { return 1; }
  std::string description() const override { return "fake target"; }
  SolverSetting default_setting() const override { return {8, 1, 30.0f}; }
  Tick ticks() const override { return 10; }
  Measurement measure(const SolverSetting& s) override {
    ++calls;
    Measurement m;
    m.ms_per_step = 0.01 * s.substeps + 0.003 * s.relax_iterations;
    const double error = 2.0 / s.work();
    m.metrics = {{"err_m", "m", error, Metric::Bound::kAtMost, limit, "error"},
                 {"kept", "", 1.0, Metric::Bound::kAtLeast, 1.0, "always 1"}};
    return m;
  }
  double limit = 0.3;
  int calls = 0;
};

SweepPlan quick_plan() {
  SweepPlan plan;
  plan.grid = SettingGrid::quick().settings();
  plan.repeats = 3;
  plan.finalists = 2;
  return plan;
}

TEST(SettingGrid, StandardGridHasCheapAndFineSettingsCheapestFirst) {
  const std::vector<SolverSetting> grid = SettingGrid::standard().settings();
  EXPECT_EQ(grid.size(), 96u);
  EXPECT_EQ(grid.front(), (SolverSetting{4, 0, 15.0f}));
  EXPECT_EQ(grid.back(), (SolverSetting{16, 4, 120.0f}));
  for (size_t i = 1; i < grid.size(); ++i) EXPECT_LE(grid[i - 1].work(), grid[i].work());
  EXPECT_NE(std::find(grid.begin(), grid.end(), SolverSetting::of(sim::WorldConfig{})), grid.end())
      << "the default setting is in the grid";
  SettingGrid repeated{{2, 2}, {1}, {30.0f, 30.0f}};
  EXPECT_EQ(repeated.settings().size(), 1u);
}

TEST(SettingGrid, ListsAreCheckedItemByItem) {
  auto ok = parse_int_list("1,2,16", 1, 64);
  ASSERT_TRUE(ok.ok());
  EXPECT_EQ(*ok, (std::vector<int32_t>{1, 2, 16}));
  EXPECT_NE(parse_int_list("0,2", 1, 64).status().message().find("0 is outside [1, 64]"),
            std::string::npos);
  EXPECT_FALSE(parse_int_list("1,,2", 1, 64).ok());
  EXPECT_FALSE(parse_int_list("two", 1, 64).ok());
  auto hertz = parse_hertz_list("15,30.5");
  ASSERT_TRUE(hertz.ok());
  EXPECT_FLOAT_EQ((*hertz)[1], 30.5f);
  EXPECT_FALSE(parse_hertz_list("0").ok());
  EXPECT_FALSE(parse_hertz_list("nan").ok());
  EXPECT_EQ((SolverSetting{2, 0, 60.0f}).label(), "substeps=2 relax=0 hertz=60");
}

TEST(Budget, ParsesReplacesAndNamesTheMetrics) {
  Budget budget;
  for (const char* bad : {"err_m", "=1", "err_m=", "err_m=abc", "err_m=inf", "err_m=1x"}) {
    EXPECT_FALSE(budget.add(bad).ok()) << bad;
  }
  ASSERT_TRUE(budget.add("err_m=0.5").ok());
  ASSERT_TRUE(budget.add("err_m=0.25").ok());  // the later one wins
  std::vector<Metric> metrics = {{"err_m", "m", 0.3, Metric::Bound::kAtMost, 1.0, ""}};
  ASSERT_TRUE(budget.check_names(metrics).ok());
  budget.apply(metrics);
  EXPECT_DOUBLE_EQ(metrics[0].limit, 0.25);
  EXPECT_TRUE(budget.overrides("err_m"));

  ASSERT_TRUE(budget.add("typo=1").ok());
  const Status unknown = budget.check_names(metrics);
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.message().find("no metric 'typo'"), std::string::npos) << unknown.message();
  EXPECT_NE(unknown.message().find("err_m (m)"), std::string::npos) << unknown.message();
}

TEST(Budget, OvershootIsRelativeAndNaNNeverPasses) {
  Metric at_most{"a", "m", 1.5, Metric::Bound::kAtMost, 1.0, ""};
  EXPECT_DOUBLE_EQ(overshoot(at_most), 0.5);
  Metric at_least{"b", "s", 2.0, Metric::Bound::kAtLeast, 4.0, ""};
  EXPECT_DOUBLE_EQ(overshoot(at_least), 0.5);
  Metric zero_limit{"c", "", 3.0, Metric::Bound::kAtMost, 0.0, ""};
  EXPECT_DOUBLE_EQ(overshoot(zero_limit), 3.0);
  Metric fell{"d", "mm", std::nan(""), Metric::Bound::kAtMost, 6.0, ""};
  EXPECT_FALSE(meets(fell));
  EXPECT_EQ(overshoot(fell), std::numeric_limits<double>::infinity());
  Metric reported{
      "e", "m", std::nan(""), Metric::Bound::kAtMost, std::numeric_limits<double>::infinity(), ""};
  EXPECT_TRUE(meets(reported)) << "a metric without a limit never fails";
}

TEST(Tuner, PicksTheCheapestSettingThatMeetsTheBudget) {
  FakeTarget target;
  const SweepPlan plan = quick_plan();
  auto result = tune(target, plan, nullptr);
  ASSERT_TRUE(result.ok()) << result.status().message();
  // Passing (error <= 0.3): (4,1) 0.25, (8,0) 0.25, (6,1) 0.167, (8,1) 0.125.
  EXPECT_EQ(result->passing, 4u);
  ASSERT_TRUE(result->pick.has_value());
  const SettingRun& pick = result->runs[*result->pick];
  EXPECT_EQ(pick.setting, (SolverSetting{4, 1, 30.0f}));
  EXPECT_TRUE(pick.pass);
  EXPECT_EQ(pick.ms_samples.size(), 3u) << "finalists are timed `repeats` times";
  EXPECT_TRUE(result->default_setting().is_default);
  EXPECT_EQ(result->default_setting().setting, (SolverSetting{8, 1, 30.0f}));
  EXPECT_EQ(result->default_setting().ms_samples.size(), 3u);
  EXPECT_EQ(result->runs.size(), 6u) << "the default is part of the quick grid";
  EXPECT_TRUE(result->repeatable);
  EXPECT_EQ(exit_code(*result), kExitFound);

  std::ostringstream text;
  print_text(target, plan, *result, text);
  EXPECT_NE(text.str().find("pick:     substeps=4 relax=1 hertz=30"), std::string::npos)
      << text.str();
  EXPECT_NE(text.str().find("set in WorldConfig: substeps = 4, relax_iterations = 1"),
            std::string::npos);
}

TEST(Tuner, UserBudgetsReplaceTheTargetsLimits) {
  FakeTarget target;
  SweepPlan plan = quick_plan();
  ASSERT_TRUE(plan.budget.add("err_m=0.2").ok());
  auto result = tune(target, plan, nullptr);
  ASSERT_TRUE(result.ok());
  ASSERT_TRUE(result->pick.has_value());
  EXPECT_EQ(result->runs[*result->pick].setting, (SolverSetting{6, 1, 30.0f}));
  EXPECT_DOUBLE_EQ(result->runs[*result->pick].metrics[0].limit, 0.2);

  std::ostringstream csv;
  write_csv(target, plan, *result, csv);
  EXPECT_NE(csv.str().find(",err_m,m,0.166666667,at_most,0.2,user,1,1,0,1,"), std::string::npos)
      << csv.str();
}

TEST(Tuner, NothingPassesNamesTheClosestSetting) {
  FakeTarget target;
  target.limit = 0.01;
  auto result = tune(target, quick_plan(), nullptr);
  ASSERT_TRUE(result.ok());
  EXPECT_FALSE(result->pick.has_value());
  ASSERT_TRUE(result->closest.has_value());
  EXPECT_EQ(result->runs[*result->closest].setting, (SolverSetting{8, 1, 30.0f}));
  EXPECT_EQ(exit_code(*result), kExitNonePasses);
  std::ostringstream json;
  print_json(target, quick_plan(), *result, json);
  EXPECT_NE(json.str().find("\"outcome\":\"none_passes\""), std::string::npos) << json.str();
  EXPECT_NE(json.str().find("\"pick\":null"), std::string::npos);
}

TEST(Tuner, UnknownBudgetMetricIsRefusedAfterOneRun) {
  FakeTarget target;
  SweepPlan plan = quick_plan();
  ASSERT_TRUE(plan.budget.add("penetration_mm=2").ok());
  auto result = tune(target, plan, nullptr);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(result.status().message().find("err_m"), std::string::npos);
  EXPECT_EQ(target.calls, 1) << "only the default ran";
}

TEST(Tuner, DefaultOutsideTheGridIsStillTheBaseline) {
  FakeTarget target;
  SweepPlan plan = quick_plan();
  plan.grid = SettingGrid{{8}, {0}, {30.0f}}.settings();
  auto result = tune(target, plan, nullptr);
  ASSERT_TRUE(result.ok());
  ASSERT_EQ(result->runs.size(), 2u);
  EXPECT_FALSE(result->default_setting().in_grid);
  ASSERT_TRUE(result->pick.has_value());
  EXPECT_EQ(result->runs[*result->pick].setting, (SolverSetting{8, 0, 30.0f}));
}

TEST(Tuner, MedianOfTimings) {
  EXPECT_DOUBLE_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(median({4.0, 1.0, 2.0, 3.0}), 2.5);
  EXPECT_DOUBLE_EQ(median({}), 0.0);
}

}  // namespace
}  // namespace rwd::tune
