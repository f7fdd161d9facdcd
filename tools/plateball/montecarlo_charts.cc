#include "montecarlo_charts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "common/svg.h"

namespace plateball::tools {
namespace {

struct ChartSeries {
  std::string label;
  std::vector<double> x, y;  // data values (> 0 are drawn)
  SvgFigure::Style style;
  bool markers = false;
};

std::string Decade(int d) {
  if (d >= 0 && d <= 3) return std::to_string(static_cast<int>(std::lround(std::pow(10.0, d))));
  return "1e" + std::to_string(d);
}

std::string Short(double v) {
  char buf[32];
  if (v == std::floor(v) && std::abs(v) < 1e7)
    std::snprintf(buf, sizeof buf, "%.0f", v);
  else
    std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// A log-log chart in pixel units (SvgFigure maps its fitted world box 1:1 onto the canvas): the
// plot box, decade ticks (or `x_ticks`), the axis labels, the legend in rows below the plot.
class LogChart {
 public:
  LogChart(const std::vector<ChartSeries>& series, std::vector<double> x_ticks)
      : series_(series), x_ticks_(std::move(x_ticks)) {
    double xl = INFINITY, xh = -INFINITY, yl = INFINITY, yh = -INFINITY;
    for (const ChartSeries& s : series)
      for (std::size_t i = 0; i < s.x.size(); ++i)
        if (s.x[i] > 0 && s.y[i] > 0 && std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
          xl = std::min(xl, std::log10(s.x[i])), xh = std::max(xh, std::log10(s.x[i]));
          yl = std::min(yl, std::log10(s.y[i])), yh = std::max(yh, std::log10(s.y[i]));
        }
    if (!std::isfinite(xl)) xl = yl = 0, xh = yh = 1;
    xlo_ = x_ticks_.empty() ? std::floor(xl) : xl - 0.1;
    xhi_ = x_ticks_.empty() ? std::max(std::ceil(xh), xlo_ + 1) : xh + 0.1;
    ylo_ = std::floor(yl);
    yhi_ = std::max(std::ceil(yh), ylo_ + 1);
    bottom_ = 58 + 17.0 * static_cast<double>(series.size());
  }

  std::string Render(const std::string& title, const std::string& x_label, const std::string& y_label) const {
    const double width_px = 760, height_px = 470 + bottom_;
    SvgFigure fig(width_px, height_px);
    fig.EqualAspect(false);
    fig.Axes(false);  // this chart draws its own axes in pixel units (svg.h)
    fig.Title(title);
    const double W = (width_px - 80) / 1.12, H = (height_px - 90) / 1.12;  // world = pixels (svg.cc's fit)
    fig.Polyline({{0, 0}, {W, 0}, {W, H}, {0, H}, {0, 0}}, {"white", 0.1, "", "none"});
    box_ = {70, bottom_, W - 15, H - 22};
    fig.Polyline({{box_[0], box_[1]}, {box_[2], box_[1]}, {box_[2], box_[3]}, {box_[0], box_[3]}, {box_[0], box_[1]}},
                 {"black", 1, "", "none"});
    Ticks(&fig);
    fig.Text({box_[0] + (box_[2] - box_[0]) / 2 - 3.2 * x_label.size(), box_[1] - 36}, x_label, 13);
    fig.Text({box_[0] - 60, box_[3] + 8}, y_label, 13);
    double row = bottom_ - 58;
    for (const ChartSeries& s : series_) {
      Draw(s, &fig);
      fig.Polyline({{box_[0], row + 4}, {box_[0] + 30, row + 4}}, s.style);
      fig.Text({box_[0] + 38, row}, s.label, 12);
      row -= 17;
    }
    return fig.Render();
  }

 private:
  Eigen::Vector2d Map(double x, double y) const {
    return {box_[0] + (std::log10(x) - xlo_) / (xhi_ - xlo_) * (box_[2] - box_[0]),
            box_[1] + (std::log10(y) - ylo_) / (yhi_ - ylo_) * (box_[3] - box_[1])};
  }
  void Ticks(SvgFigure* fig) const {
    const SvgFigure::Style grid{"#dddddd", 0.8, "", "none"};
    for (int d = static_cast<int>(ylo_); d <= static_cast<int>(yhi_); ++d) {
      const double y = Map(std::pow(10.0, xlo_), std::pow(10.0, d)).y();
      fig->Polyline({{box_[0], y}, {box_[2], y}}, grid);
      fig->Text({box_[0] - 8 - 6.6 * Decade(d).size(), y - 4}, Decade(d), 11);
    }
    std::vector<double> xs = x_ticks_;
    if (xs.empty())
      for (int d = static_cast<int>(xlo_); d <= static_cast<int>(xhi_); ++d) xs.push_back(std::pow(10.0, d));
    for (double v : xs) {
      const double x = Map(v, std::pow(10.0, ylo_)).x();
      fig->Polyline({{x, box_[1]}, {x, box_[3]}}, grid);
      const std::string t = x_ticks_.empty() ? Decade(static_cast<int>(std::lround(std::log10(v)))) : Short(v);
      fig->Text({x - 3.3 * t.size(), box_[1] - 16}, t, 11);
    }
  }
  void Draw(const ChartSeries& s, SvgFigure* fig) const {
    std::vector<Eigen::Vector2d> pts;
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (s.x[i] > 0 && s.y[i] > 0 && std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
        pts.push_back(Map(s.x[i], s.y[i]));
    if (pts.size() >= 2) fig->Polyline(pts, s.style);
    if (s.markers)
      for (const auto& p : pts) fig->Marker(p, 3.2, {s.style.stroke, 1, "", s.style.stroke});
  }

  std::vector<ChartSeries> series_;
  std::vector<double> x_ticks_;
  double xlo_ = 0, xhi_ = 1, ylo_ = 0, yhi_ = 1, bottom_ = 60;
  mutable std::array<double, 4> box_{};  // left, bottom, right, top (pixels, y up)
};

std::string Color(const MonteCarloProblem& p, int scenario, ExecutionStrategy s) {
  static const char* kStrategy[] = {"#c0392b", "#1f5fbf", "#1e8449"};
  static const char* kPalette[] = {
      "#c0392b", "#1f5fbf", "#1e8449", "#8e44ad", "#d68910", "#17a589", "#7f8c8d", "#2c3e50"};
  if (p.scenarios.size() == 1) return kStrategy[static_cast<int>(s)];
  const std::size_t k =
      static_cast<std::size_t>(scenario) * p.strategies.size() +
      static_cast<std::size_t>(std::find(p.strategies.begin(), p.strategies.end(), s) - p.strategies.begin());
  return kPalette[k % 8];
}

// Error against n: the colour names the scenario (the strategy when there is one scenario), the
// dash the strategy (open loop dashed, feedback solid, exact re-solve dotted).
SvgFigure::Style SweepStyle(const MonteCarloProblem& p, int scenario, ExecutionStrategy s) {
  static const char* kPalette[] = {
      "#c0392b", "#1f5fbf", "#1e8449", "#8e44ad", "#d68910", "#17a589", "#7f8c8d", "#2c3e50"};
  static const char* kDash[] = {"8,4", "", "2,3"};
  const std::string color = p.scenarios.size() == 1 ? Color(p, scenario, s) : kPalette[scenario % 8];
  return {color, 1.8, kDash[static_cast<int>(s)], "none"};
}

std::string CellName(const MonteCarloProblem& p, int scenario, ExecutionStrategy s) {
  return ToString(s) +
         (p.scenarios.size() > 1 ? " (" + p.scenarios[static_cast<std::size_t>(scenario)].name + ")" : "");
}

// P(value > x) at the sorted values: the empirical survival function.
ChartSeries Survival(std::vector<double> v, const std::string& label, const SvgFigure::Style& style) {
  std::sort(v.begin(), v.end());
  ChartSeries s{label, {}, {}, style, false};
  const double n = static_cast<double>(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    s.x.push_back(v[i]);
    s.y.push_back((n - static_cast<double>(i)) / n);
  }
  return s;
}

}  // namespace

std::string RenderErrorDistributions(const MonteCarloProblem& problem,
                                     const MonteCarloSummary& summary,
                                     const NominalPlan& plan) {
  std::vector<ChartSeries> series;
  const int n = summary.cells.empty() ? 0 : summary.cells.front().n;
  for (const MonteCarloCell& c : summary.cells) {
    if (c.n != n) continue;
    std::vector<double> ori, pos;
    for (const TrialRecord& r : summary.records)
      if (r.n == n && r.scenario == c.scenario && r.strategy == c.strategy && r.status == ExecutionStatus::kCompleted) {
        ori.push_back(r.orientation_error);
        pos.push_back(r.position_error);
      }
    const std::string color = Color(problem, c.scenario, c.strategy), name = CellName(problem, c.scenario, c.strategy);
    if (!c.orientation_error || !c.position_error) {  // an empty legend entry says why nothing is drawn
      series.push_back({name + ": no trial completed", {}, {}, {color, 1.8, "", "none"}, false});
      continue;
    }
    series.push_back(Survival(ori,
                              name + ": orientation error (rad), median " + Short(c.orientation_error->median),
                              {color, 1.8, "", "none"}));
    series.push_back(Survival(
        pos, name + ": position error, median " + Short(c.position_error->median), {color, 1.4, "6,4", "none"}));
  }
  const double floor_p = 1.0 / std::max(1, problem.trials);
  series.push_back({"plan without errors: orientation error " + Short(plan.plan_orientation_error) + " rad",
                    {plan.plan_orientation_error, plan.plan_orientation_error},
                    {floor_p, 1.0},
                    {"black", 1.2, "2,3", "none"},
                    false});
  return LogChart(series, {})
      .Render("Final errors, n = " + std::to_string(n) + ", " + std::to_string(problem.trials) + " trials per strategy",
              "final error e (orientation: rad; position: ball radii)",
              "P(error > e)");
}

std::string RenderErrorAgainstN(const MonteCarloProblem& problem, const MonteCarloSummary& summary) {
  std::vector<ChartSeries> series;
  std::vector<double> ticks;
  for (const SweepSeries& w : summary.sweeps) {
    std::string missing;  // the n without data, named in the legend and not drawn
    ChartSeries s{"", {}, {}, SweepStyle(problem, w.scenario, w.strategy), true};
    ticks.clear();
    for (std::size_t i = 0; i < w.n.size(); ++i) {
      ticks.push_back(w.n[i]);
      if (w.Missing(i)) {
        missing += (missing.empty() ? "" : ", ") + std::to_string(w.n[i]);
        continue;
      }
      s.x.push_back(w.n[i]);
      s.y.push_back(*w.median_orientation_error[i]);
    }
    s.label = CellName(problem, w.scenario, w.strategy) + ": median, slope " + (w.slope ? Short(*w.slope) : "none") +
              (missing.empty() ? "" : " (no trial completed at n = " + missing + ")");
    series.push_back(s);
  }
  if (!summary.sweeps.empty()) {
    const SweepSeries& w = summary.sweeps.front();
    series.push_back({"plan without errors (Theorem 2.6), slope " + (w.plan_slope ? Short(*w.plan_slope) : "none"),
                      ticks,
                      w.plan_orientation_error,
                      {"black", 2.4, "1,3", "none"},
                      true});
  }
  return LogChart(series, ticks)
      .Render("Final orientation error against the number of impulses n",
              "impulses n",
              "median final orientation error (rad)");
}

}  // namespace plateball::tools
