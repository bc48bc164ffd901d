// SPDX-License-Identifier: MIT
#include "rewind/tune/tune_chart.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace rwd::tune {
namespace {

// A gnuplot single-quoted string: '' stands for one quote.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += '\'';
    out += c;
  }
  return out + "'";
}

std::string short_label(const SolverSetting& s) {
  std::ostringstream out;
  out << "s" << s.substeps << " r" << s.relax_iterations << " hz" << s.contact_hertz;
  return out.str();
}

struct Point {
  double ms;
  double value;
  std::string label;
};

// One panel: the settings split by what they are, values that are not
// finite (a structure that fell measures NaN) drawn at the top.
void panel(std::ostringstream& out, size_t index, const TuneResult& result, const Metric& shape) {
  std::vector<double> finite;
  for (const SettingRun& run : result.runs) {
    if (run.error.empty() && index < run.metrics.size() &&
        std::isfinite(run.metrics[index].value)) {
      finite.push_back(run.metrics[index].value);
    }
  }
  const bool limited = has_limit(shape);
  double top = finite.empty() ? 1.0 : *std::max_element(finite.begin(), finite.end());
  if (limited) top = std::max(top, shape.limit);
  const double cap = top > 0.0 ? top * 1.5 : 1.0;
  const bool all_positive =
      !finite.empty() && std::all_of(finite.begin(), finite.end(), [](double v) { return v > 0; });
  const double low = finite.empty() ? 0.0 : *std::min_element(finite.begin(), finite.end());
  const bool logy = all_positive && top / low > 100.0 && (!limited || shape.limit > 0.0);

  std::vector<Point> sets[4];  // misses, meets, default, pick
  bool capped = false;
  for (size_t i = 0; i < result.runs.size(); ++i) {
    const SettingRun& run = result.runs[i];
    if (!run.error.empty() || index >= run.metrics.size()) continue;
    double v = run.metrics[index].value;
    if (!std::isfinite(v)) {
      v = cap;
      capped = true;
    }
    const Point p{run.ms_per_step, v, short_label(run.setting)};
    sets[run.pass ? 1 : 0].push_back(p);
    if (run.is_default) sets[2].push_back(p);
    if (result.pick == i) sets[3].push_back(p);
  }
  static const char* const kNames[4] = {"misses", "meets", "default", "pick"};
  for (int s = 0; s < 4; ++s) {
    out << "$" << kNames[s] << index << " << EOD\n";
    // Labels are double-quoted: that is how a data line holds a column with spaces.
    for (const Point& p : sets[s]) out << p.ms << " " << p.value << " \"" << p.label << "\"\n";
    out << "EOD\n";
  }

  std::string title = shape.name + (shape.unit.empty() ? "" : " (" + shape.unit + ")");
  if (limited) {
    std::ostringstream limit;
    limit << (shape.bound == Metric::Bound::kAtMost ? ", budget at most " : ", budget at least ")
          << shape.limit;
    title += limit.str();
  }
  if (capped) title += "; not a number: drawn at the top";
  out << "set title " << quoted(title) << "\n";
  out << "set xlabel 'ms per step'\nset ylabel " << quoted(shape.unit) << "\n";
  out << "set logscale x\n" << (logy ? "set logscale y\n" : "unset logscale y\n");
  out << "set grid\nset key outside right top\n";
  std::vector<std::string> plots;
  auto add = [&](int s, const std::string& style) {
    if (!sets[s].empty())
      plots.push_back("$" + std::string(kNames[s]) + std::to_string(index) + style);
  };
  add(0, " using 1:2 with points pt 6 ps 0.8 lc rgb 'gray55' title 'misses the budget'");
  add(1, " using 1:2 with points pt 7 ps 0.8 lc rgb '#1f77b4' title 'meets the budget'");
  add(2, " using 1:2 with points pt 4 ps 2.0 lw 2 lc rgb '#ff7f0e' title 'default'");
  // The pick's label goes up and left, the default's down and right: they
  // are often neighbours.
  add(2, " using 1:2:3 with labels offset 1.4,-1.0 left font ',9' tc rgb '#ff7f0e' notitle");
  add(3, " using 1:2 with points pt 3 ps 2.4 lw 2 lc rgb '#d62728' title 'pick'");
  add(3, " using 1:2:3 with labels offset -1.4,1.0 right font ',9' tc rgb '#d62728' notitle");
  if (limited) {
    std::ostringstream line;
    line << shape.limit << " with lines dt 2 lw 1.5 lc rgb 'gray25' title 'budget'";
    plots.push_back(line.str());
  }
  out << "plot ";
  for (size_t i = 0; i < plots.size(); ++i) out << (i ? ", \\\n  " : "") << plots[i];
  out << "\n";
}

}  // namespace

bool gnuplot_available() {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return false;
  std::istringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    if (::access((dir + "/gnuplot").c_str(), X_OK) == 0) return true;
  }
  return false;
}

std::string chart_script(const TuneTarget& target, const TuneResult& result,
                         const std::string& svg_path) {
  const std::vector<Metric>& metrics = result.default_setting().metrics;
  const size_t panels = std::max<size_t>(1, metrics.size());
  std::ostringstream out;
  out << "set terminal svg size 820," << 80 + 330 * panels
      << " dynamic noenhanced font 'sans,11' background rgb 'white'\n";
  out << "set output " << quoted(svg_path) << "\n";
  std::ostringstream title;
  title << target.kind() << " " << target.name() << " " << target.size() << ": error against cost, "
        << result.runs.size() << " settings; ";
  if (result.pick) {
    title << "pick " << result.runs[*result.pick].setting.label();
  } else {
    title << "no setting meets the budget";
  }
  out << "set multiplot layout " << panels << ",1 title " << quoted(title.str()) << "\n";
  for (size_t i = 0; i < metrics.size(); ++i) panel(out, i, result, metrics[i]);
  out << "unset multiplot\n";
  return out.str();
}

Status write_chart(const TuneTarget& target, const TuneResult& result,
                   const std::string& svg_path) {
  const std::string script = chart_script(target, result, svg_path);
  std::FILE* gnuplot = ::popen("gnuplot", "w");
  if (gnuplot == nullptr) return Status::Error(ErrorCode::kIo, "cannot start gnuplot");
  const size_t written = std::fwrite(script.data(), 1, script.size(), gnuplot);
  const int status = ::pclose(gnuplot);
  if (written != script.size() || status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    return Status::Error(ErrorCode::kIo, "gnuplot could not draw " + svg_path);
  }
  return Status::Ok();
}

}  // namespace rwd::tune
