// SPDX-License-Identifier: MIT
// The /metrics body is valid Prometheus text exposition (0.0.4): every
// family has one # HELP and one # TYPE line before its samples, names and
// labels are well formed, values parse, counters end in _total, and the
// tick histogram's buckets are cumulative up to +Inf == _count.
#include "rewind/server/metrics_text.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <string>

namespace rwd::server {
namespace {

struct Family {
  std::string type;
  bool help = false;
  std::map<std::string, double> samples;  // name with labels -> value
};

bool is_name(const std::string& name) {
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) return false;
  for (const char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != ':') return false;
  }
  return true;
}

// The family a sample belongs to: histograms own _bucket, _sum and _count.
std::string family_of(const std::string& name, const std::map<std::string, Family>& families) {
  for (const char* suffix : {"_bucket", "_sum", "_count"}) {
    const std::string s = suffix;
    if (name.size() > s.size() && name.ends_with(s)) {
      const std::string base = name.substr(0, name.size() - s.size());
      auto it = families.find(base);
      if (it != families.end() && it->second.type == "histogram") return base;
    }
  }
  return name;
}

// Parses the exposition text, failing the test on any malformed line.
std::map<std::string, Family> parse(const std::string& text) {
  std::map<std::string, Family> families;
  std::set<std::string> started;  // families whose samples have begun
  std::istringstream in(text);
  EXPECT_TRUE(text.ends_with("\n"));
  for (std::string line; std::getline(in, line);) {
    SCOPED_TRACE(line);
    EXPECT_FALSE(line.empty());
    if (line.starts_with("# HELP ") || line.starts_with("# TYPE ")) {
      std::istringstream words(line.substr(7));
      std::string name, rest;
      words >> name;
      std::getline(words, rest);
      EXPECT_TRUE(is_name(name));
      EXPECT_TRUE(name.starts_with("rewind_"));
      EXPECT_FALSE(started.count(name)) << "metadata after samples";
      Family& family = families[name];
      if (line[2] == 'H') {
        EXPECT_FALSE(family.help) << "second HELP";
        EXPECT_GT(rest.size(), 1u);
        family.help = true;
      } else {
        EXPECT_TRUE(family.type.empty()) << "second TYPE";
        family.type = rest.substr(1);
        EXPECT_TRUE(family.type == "counter" || family.type == "gauge" ||
                    family.type == "histogram")
            << family.type;
      }
      continue;
    }
    EXPECT_NE(line[0], '#');
    const size_t space = line.rfind(' ');
    EXPECT_NE(space, std::string::npos);
    const std::string series = line.substr(0, space);
    const std::string value = line.substr(space + 1);
    char* end = nullptr;
    const double number = std::strtod(value.c_str(), &end);
    EXPECT_EQ(*end, '\0') << "value " << value;
    const size_t brace = series.find('{');
    const std::string name = series.substr(0, brace);
    EXPECT_TRUE(is_name(name));
    if (brace != std::string::npos) {
      // Labels name="value" joined by commas, values without quotes.
      const std::string labels = series.substr(brace + 1);
      EXPECT_TRUE(labels.ends_with("\"}"));
      std::istringstream pairs(labels.substr(0, labels.size() - 1));
      for (std::string pair; std::getline(pairs, pair, ',');) {
        const size_t equals = pair.find("=\"");
        EXPECT_NE(equals, std::string::npos) << pair;
        if (equals == std::string::npos) continue;
        EXPECT_TRUE(is_name(pair.substr(0, equals))) << pair;
        EXPECT_TRUE(pair.ends_with("\"")) << pair;
        EXPECT_EQ(pair.find('"', equals + 2), pair.size() - 1) << pair;
      }
    }
    const std::string family_name = family_of(name, families);
    auto it = families.find(family_name);
    EXPECT_NE(it, families.end()) << "sample without # TYPE";
    if (it == families.end()) continue;
    EXPECT_TRUE(it->second.help) << "sample without # HELP";
    if (it->second.type == "counter") {
      EXPECT_TRUE(name.ends_with("_total"));
    }
    started.insert(family_name);
    EXPECT_FALSE(it->second.samples.count(series)) << "repeated series";
    it->second.samples[series] = number;
  }
  return families;
}

MetricsSample sample_with_counts() {
  MetricsSample sample;
  sample.match = "m";
  sample.stats.ticks_final = 600;
  sample.stats.rollbacks = 3;
  sample.stats.rejected_packets = 7;
  sample.stats.players_joined = 2;
  sample.stats.bytes_out = 123456789012;
  sample.stats.secure_dropped = 42;
  sample.phase = MatchHost::Phase::kRunning;
  sample.players_connected = 1;
  sample.tick_time.observe(std::chrono::microseconds(10));
  sample.tick_time.observe(std::chrono::microseconds(30));
  sample.tick_time.observe(std::chrono::microseconds(25));  // on a bound: counts in it
  sample.tick_time.observe(std::chrono::milliseconds(20));  // beyond the last bound
  return sample;
}

MetricsSample empty_sample() {
  MetricsSample sample;
  sample.match = "m";
  return sample;
}

std::string render_one(const MetricsSample& sample) {
  return render_metrics(std::span<const MetricsSample>(&sample, 1));
}

TEST(MetricsText, IsValidExpositionWithHelpAndTypeForEveryFamily) {
  const std::map<std::string, Family> families = parse(render_one(sample_with_counts()));
  for (const auto& [name, family] : families) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(family.help);
    EXPECT_FALSE(family.type.empty());
    EXPECT_FALSE(family.samples.empty());
  }
  for (const char* name : {"rewind_matches",
                           "rewind_match_phase",
                           "rewind_players_joined",
                           "rewind_players_connected",
                           "rewind_ticks_final_total",
                           "rewind_rollbacks_total",
                           "rewind_resimulated_ticks_total",
                           "rewind_late_inputs_total",
                           "rewind_substituted_inputs_total",
                           "rewind_rejected_inputs_total",
                           "rewind_rejected_packets_total",
                           "rewind_desync_reports_total",
                           "rewind_resyncs_sent_total",
                           "rewind_packets_in_total",
                           "rewind_packets_out_total",
                           "rewind_bytes_in_total",
                           "rewind_bytes_out_total",
                           "rewind_secure_challenges_total",
                           "rewind_secure_sessions_total",
                           "rewind_secure_refused_total",
                           "rewind_secure_dropped_total",
                           "rewind_tick_seconds",
                           "rewind_tick_seconds_max"}) {
    EXPECT_TRUE(families.count(name)) << name;
  }
  EXPECT_EQ(families.at("rewind_ticks_final_total").type, "counter");
  EXPECT_EQ(families.at("rewind_players_joined").type, "gauge");
  EXPECT_EQ(families.at("rewind_tick_seconds").type, "histogram");
}

TEST(MetricsText, CarriesTheCountersAndGauges) {
  const std::map<std::string, Family> f = parse(render_one(sample_with_counts()));
  EXPECT_EQ(f.at("rewind_matches").samples.at("rewind_matches"), 1);
  EXPECT_EQ(f.at("rewind_ticks_final_total").samples.at("rewind_ticks_final_total{match=\"m\"}"),
            600);
  EXPECT_EQ(f.at("rewind_rollbacks_total").samples.at("rewind_rollbacks_total{match=\"m\"}"), 3);
  EXPECT_EQ(f.at("rewind_rejected_packets_total")
                .samples.at("rewind_rejected_packets_total{match=\"m\"}"),
            7);
  EXPECT_EQ(
      f.at("rewind_secure_dropped_total").samples.at("rewind_secure_dropped_total{match=\"m\"}"),
      42);
  EXPECT_EQ(f.at("rewind_players_joined").samples.at("rewind_players_joined{match=\"m\"}"), 2);
  EXPECT_EQ(f.at("rewind_players_connected").samples.at("rewind_players_connected{match=\"m\"}"),
            1);
  // Large counters print as integers, not in exponent form.
  EXPECT_NE(
      render_one(sample_with_counts()).find("\nrewind_bytes_out_total{match=\"m\"} 123456789012\n"),
      std::string::npos);
  const auto& phase = f.at("rewind_match_phase").samples;
  EXPECT_EQ(phase.size(), 4u);
  EXPECT_EQ(phase.at("rewind_match_phase{match=\"m\",phase=\"running\"}"), 1);
  EXPECT_EQ(phase.at("rewind_match_phase{match=\"m\",phase=\"lobby\"}"), 0);
  EXPECT_EQ(phase.at("rewind_match_phase{match=\"m\",phase=\"closing\"}"), 0);
  EXPECT_EQ(phase.at("rewind_match_phase{match=\"m\",phase=\"ended\"}"), 0);
}

TEST(MetricsText, TickHistogramIsCumulativeWithSumCountAndMax) {
  const std::map<std::string, Family> f = parse(render_one(sample_with_counts()));
  const auto& h = f.at("rewind_tick_seconds").samples;
  EXPECT_EQ(h.at("rewind_tick_seconds_bucket{match=\"m\",le=\"2.5e-05\"}"), 2);
  EXPECT_EQ(h.at("rewind_tick_seconds_bucket{match=\"m\",le=\"5e-05\"}"), 3);
  EXPECT_EQ(h.at("rewind_tick_seconds_bucket{match=\"m\",le=\"0.0001\"}"), 3);
  EXPECT_EQ(h.at("rewind_tick_seconds_bucket{match=\"m\",le=\"0.01\"}"), 3);
  EXPECT_EQ(h.at("rewind_tick_seconds_bucket{match=\"m\",le=\"+Inf\"}"), 4);
  EXPECT_EQ(h.at("rewind_tick_seconds_count{match=\"m\"}"), 4);
  EXPECT_DOUBLE_EQ(h.at("rewind_tick_seconds_sum{match=\"m\"}"), 0.020065);
  EXPECT_EQ(h.size(), TickHistogram().bucket_total() + 2);
  // Ordered by their bounds, the buckets never decrease.
  std::map<double, double> by_bound;
  for (const auto& [series, value] : h) {
    const size_t le = series.find("le=\"");
    if (le != std::string::npos) by_bound[std::strtod(series.c_str() + le + 4, nullptr)] = value;
  }
  EXPECT_EQ(by_bound.size(), TickHistogram().bucket_total());
  double previous = 0;
  for (const auto& [bound, value] : by_bound) {
    EXPECT_GE(value, previous) << bound;
    previous = value;
  }
  EXPECT_DOUBLE_EQ(
      f.at("rewind_tick_seconds_max").samples.at("rewind_tick_seconds_max{match=\"m\"}"), 0.02);
}

TEST(MetricsText, ATickHistogramWithNoTicksIsAllZero) {
  const std::map<std::string, Family> f = parse(render_one(empty_sample()));
  for (const auto& [series, value] : f.at("rewind_tick_seconds").samples) {
    EXPECT_EQ(value, 0) << series;
  }
  EXPECT_EQ(
      f.at("rewind_match_phase").samples.at("rewind_match_phase{match=\"m\",phase=\"lobby\"}"), 1);
}

TEST(MetricsText, SeveralMatchesAreSeriesOfOneFamily) {
  MetricsSample first = sample_with_counts();
  MetricsSample second;
  second.match = "duel-2";
  second.stats.ticks_final = 40;
  second.phase = MatchHost::Phase::kEnded;
  const MetricsSample both[] = {first, second};
  const std::map<std::string, Family> f = parse(render_metrics(both));
  const auto& ticks = f.at("rewind_ticks_final_total").samples;
  EXPECT_EQ(ticks.size(), 2u);
  EXPECT_EQ(ticks.at("rewind_ticks_final_total{match=\"m\"}"), 600);
  EXPECT_EQ(ticks.at("rewind_ticks_final_total{match=\"duel-2\"}"), 40);
  EXPECT_EQ(
      f.at("rewind_match_phase").samples.at("rewind_match_phase{match=\"duel-2\",phase=\"ended\"}"),
      1);
  // An ended match is still reported but no longer counted as hosted.
  EXPECT_EQ(f.at("rewind_matches").samples.at("rewind_matches"), 1);
  EXPECT_EQ(f.at("rewind_tick_seconds").samples.size(), 2 * (TickHistogram().bucket_total() + 2));
}

TEST(MetricsText, NoMatchesStillDescribesEveryFamily) {
  const std::map<std::string, Family> f = parse(render_metrics({}));
  EXPECT_EQ(f.at("rewind_matches").samples.at("rewind_matches"), 0);
  EXPECT_TRUE(f.count("rewind_ticks_final_total"));
  EXPECT_TRUE(f.at("rewind_ticks_final_total").help);
  EXPECT_TRUE(f.count("rewind_tick_lateness_seconds"));
  EXPECT_FALSE(f.count("rewind_tick_load"));  // process figures only when given
}

TEST(MetricsText, TickLatenessAndSlippedTicksPerMatch) {
  MetricsSample sample = sample_with_counts();
  sample.tick_lateness.observe(std::chrono::microseconds(40));
  sample.tick_lateness.observe(std::chrono::microseconds(80));
  sample.tick_lateness.observe(std::chrono::milliseconds(20));  // more than a 60 Hz period
  sample.ticks_behind = 1;
  sample.stats.ticks_late = 1;
  sample.stats.ticks_missed = 12;
  const std::map<std::string, Family> f = parse(render_one(sample));
  const auto& h = f.at("rewind_tick_lateness_seconds").samples;
  EXPECT_EQ(f.at("rewind_tick_lateness_seconds").type, "histogram");
  EXPECT_EQ(h.at("rewind_tick_lateness_seconds_bucket{match=\"m\",le=\"5e-05\"}"), 1);
  EXPECT_EQ(h.at("rewind_tick_lateness_seconds_bucket{match=\"m\",le=\"0.0001\"}"), 2);
  EXPECT_EQ(h.at("rewind_tick_lateness_seconds_bucket{match=\"m\",le=\"0.01\"}"), 2);
  EXPECT_EQ(h.at("rewind_tick_lateness_seconds_bucket{match=\"m\",le=\"0.025\"}"), 3);
  EXPECT_EQ(h.at("rewind_tick_lateness_seconds_bucket{match=\"m\",le=\"+Inf\"}"), 3);
  EXPECT_EQ(h.at("rewind_tick_lateness_seconds_count{match=\"m\"}"), 3);
  EXPECT_DOUBLE_EQ(h.at("rewind_tick_lateness_seconds_sum{match=\"m\"}"), 0.02012);
  EXPECT_EQ(h.size(), sample.tick_lateness.bucket_total() + 2);
  EXPECT_EQ(f.at("rewind_ticks_late_total").samples.at("rewind_ticks_late_total{match=\"m\"}"), 1);
  EXPECT_EQ(f.at("rewind_ticks_missed_total").samples.at("rewind_ticks_missed_total{match=\"m\"}"),
            12);
  EXPECT_EQ(f.at("rewind_ticks_behind").type, "gauge");
  EXPECT_EQ(f.at("rewind_ticks_behind").samples.at("rewind_ticks_behind{match=\"m\"}"), 1);
}

TEST(MetricsText, TheProcessLoadIsUnlabelled) {
  ProcessSample process;
  process.tick_load = 0.5;
  process.tick_budget = 0.75;
  process.overloaded = true;
  process.healthy = false;
  process.matches_refused = 3;
  const MetricsSample sample = sample_with_counts();
  const std::map<std::string, Family> f =
      parse(render_metrics(std::span<const MetricsSample>(&sample, 1), &process));
  EXPECT_DOUBLE_EQ(f.at("rewind_tick_load").samples.at("rewind_tick_load"), 0.5);
  EXPECT_DOUBLE_EQ(f.at("rewind_tick_budget").samples.at("rewind_tick_budget"), 0.75);
  EXPECT_EQ(f.at("rewind_overloaded").samples.at("rewind_overloaded"), 1);
  EXPECT_EQ(f.at("rewind_healthy").samples.at("rewind_healthy"), 0);
  EXPECT_EQ(f.at("rewind_matches_refused_total").type, "counter");
  EXPECT_EQ(f.at("rewind_matches_refused_total").samples.at("rewind_matches_refused_total"), 3);
}

}  // namespace
}  // namespace rwd::server
