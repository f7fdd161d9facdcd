// `plateball identify TRACK [PROBLEM.json]`: fit lambda, mu and the initial state to a measured
// track of the contact point (identify.h, docs/identify.md) and print the result as JSON.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/command_registry.h"
#include "common/exit_codes.h"
#include "common/input_file.h"
#include "common/json_output.h"
#include "common/number_format.h"
#include "common/output_file.h"
#include "common/problem_options.h"
#include "common/svg.h"
#include "plateball/free_motion.h"
#include "plateball/identify.h"
#include "plateball/problem.h"
#include "plateball/so3.h"

namespace plateball::tools {
namespace {

struct IdentifyCliOptions {
  std::string track;
  std::string problem;
  std::string out;
  std::string svg;
  double radius = 1.0;
  std::vector<double> impulses;
  bool guess = false;
  bool no_profile = false;
  long long threads = 0;
  CLI::Option* radius_opt = nullptr;
  CLI::Option* impulses_opt = nullptr;
};

[[noreturn]] void TrackError(const std::string& file,
                             const std::string& field,
                             const std::string& value,
                             const std::string& what) {
  ThrowInvalidInput(file + ": " + field, value, what);
}

// ------------------------------------------------------------------ reading the track

/// One number of a CSV cell: the whole cell must parse.
double ParseCell(const std::string& file, const std::string& field, const std::string& cell) {
  const char* begin = cell.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (end == begin || *end != '\0') TrackError(file, field, "\"" + cell + "\"", "not a number");
  return v;
}

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  const auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

std::vector<std::string> SplitCells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) cells.push_back(Trim(cell));
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

/// The CSV columns: t, x, y required, the rest optional; an orientation (qw, qx, qy, qz) and a
/// body rate (wx, wy, wz) come with all their columns or none.
enum CsvColumn {
  kT,
  kX,
  kY,
  kSigma,
  kSpin,
  kSigmaSpin,
  kQw,
  kQx,
  kQy,
  kQz,
  kSigmaOrientation,
  kWx,
  kWy,
  kWz,
  kSigmaBodyRate,
  kColumns
};
constexpr const char* kCsvNames[kColumns] = {"t",
                                             "x",
                                             "y",
                                             "sigma",
                                             "spin",
                                             "sigma_spin",
                                             "qw",
                                             "qx",
                                             "qy",
                                             "qz",
                                             "sigma_orientation",
                                             "wx",
                                             "wy",
                                             "wz",
                                             "sigma_body_rate"};
constexpr const char* kCsvColumnList =
    "t, x, y and optionally sigma, spin, sigma_spin, qw, qx, qy, qz, sigma_orientation, wx, wy, wz and sigma_body_rate";

/// Every column of a group [first, last] or none (the header's mixed columns).
void RequireGroup(const std::string& file, const int* col, int first, int last, const char* what) {
  for (int m = first; m <= last; ++m)
    for (int k = first; k <= last; ++k)
      if (col[m] >= 0 && col[k] < 0)
        TrackError(file,
                   std::string("header column ") + kCsvNames[k],
                   "(missing)",
                   std::string("column ") + kCsvNames[m] + " is given: " + what);
}

/// CSV with a header line naming the columns (kCsvColumnList; '#' lines are comments).
IdentifyProblem ReadTrackCsv(const std::string& file, const std::string& text) {
  std::stringstream in(text);
  std::string line;
  std::vector<std::string> columns;
  IdentifyProblem p;
  int col[kColumns];
  std::fill(col, col + kColumns, -1);
  while (std::getline(in, line)) {
    const std::string trimmed = Trim(line);
    if (trimmed.empty() || trimmed[0] == '#') continue;
    const std::vector<std::string> cells = SplitCells(trimmed);
    if (columns.empty()) {
      columns = cells;
      for (std::size_t c = 0; c < cells.size(); ++c) {
        int k = -1;
        for (int m = 0; m < kColumns; ++m)
          if (cells[c] == kCsvNames[m]) k = m;
        if (k < 0)
          TrackError(file,
                     "header column " + std::to_string(c),
                     "\"" + cells[c] + "\"",
                     std::string("unknown column (the columns are ") + kCsvColumnList + ")");
        if (col[k] >= 0)
          TrackError(file, "header column " + std::to_string(c), "\"" + cells[c] + "\"", "repeated column");
        col[k] = static_cast<int>(c);
      }
      for (int m = 0; m < 3; ++m)
        if (col[m] < 0)
          TrackError(
              file, std::string("header column ") + kCsvNames[m], "(missing)", "the columns t, x and y are required");
      RequireGroup(file, col, kQw, kQz, "an orientation is the unit quaternion qw, qx, qy, qz (all four columns)");
      RequireGroup(file, col, kWx, kWz, "a body rate has the three columns wx, wy, wz");
      if (col[kSigmaOrientation] >= 0 && col[kQw] < 0)
        TrackError(file, "header column sigma_orientation", "(given)", "needs the orientation columns qw, qx, qy, qz");
      if (col[kSigmaBodyRate] >= 0 && col[kWx] < 0)
        TrackError(file, "header column sigma_body_rate", "(given)", "needs the body-rate columns wx, wy, wz");
      continue;
    }
    const std::size_t row = p.t.size();
    const std::string r = "[" + std::to_string(row) + "]";
    if (cells.size() != columns.size())
      TrackError(file,
                 "row" + r,
                 std::to_string(cells.size()) + " cells",
                 "must have " + std::to_string(columns.size()) + " cells like the header");
    auto cell = [&](int k) { return ParseCell(file, kCsvNames[k] + r, cells[static_cast<std::size_t>(col[k])]); };
    p.t.push_back(cell(kT));
    p.x.emplace_back(cell(kX), cell(kY));
    if (col[kSigma] >= 0) p.sigma.push_back(cell(kSigma));
    if (col[kSpin] >= 0) p.spin.push_back(cell(kSpin));
    if (col[kSigmaSpin] >= 0) p.sigma_spin.push_back(cell(kSigmaSpin));
    if (col[kQw] >= 0) p.orientation.emplace_back(cell(kQw), cell(kQx), cell(kQy), cell(kQz));
    if (col[kSigmaOrientation] >= 0) p.sigma_orientation.push_back(cell(kSigmaOrientation));
    if (col[kWx] >= 0) p.body_rate.emplace_back(cell(kWx), cell(kWy), cell(kWz));
    if (col[kSigmaBodyRate] >= 0) p.sigma_body_rate.push_back(cell(kSigmaBodyRate));
  }
  if (columns.empty()) TrackError(file, "(document)", "(empty)", "no header line t,x,y");
  return p;
}

/// JSON {"t": [...], "x": [[x, y], ...], "sigma": [...], "impulse_times": [...], "spin": [...],
/// "sigma_spin": [...], "orientation": [[w, x, y, z], ...], "sigma_orientation": [...],
/// "body_rate": [[wx, wy, wz], ...], "sigma_body_rate": [...]} (all but t and x optional).
IdentifyProblem ReadTrackJson(const std::string& file, const std::string& text) {
  using nlohmann::json;
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    TrackError(file, "(document)", "(see message)", std::string("malformed JSON: ") + e.what());
  }
  if (!doc.is_object())
    TrackError(file, "(document)", "(not an object)", "must be an object {\"t\": [...], \"x\": [[x, y], ...]}");
  const char* keys[] = {"t",
                        "x",
                        "sigma",
                        "impulse_times",
                        "spin",
                        "sigma_spin",
                        "orientation",
                        "sigma_orientation",
                        "body_rate",
                        "sigma_body_rate"};
  for (auto it = doc.begin(); it != doc.end(); ++it)
    if (std::find(std::begin(keys), std::end(keys), it.key()) == std::end(keys))
      TrackError(file,
                 it.key(),
                 "(any)",
                 "unknown key (a track has t, x and optionally sigma, impulse_times, spin, sigma_spin, orientation, "
                 "sigma_orientation, body_rate and sigma_body_rate)");
  for (const char* key : {"t", "x"})
    if (!doc.contains(key) || !doc[key].is_array()) TrackError(file, key, "(missing)", "required array");
  IdentifyProblem p;
  auto number = [&](const json& v, const std::string& field) {
    if (!v.is_number()) TrackError(file, field, v.dump(), "must be a number");
    return v.get<double>();
  };
  for (std::size_t i = 0; i < doc["t"].size(); ++i) p.t.push_back(number(doc["t"][i], "t[" + std::to_string(i) + "]"));
  for (std::size_t i = 0; i < doc["x"].size(); ++i) {
    const json& q = doc["x"][i];
    const std::string f = "x[" + std::to_string(i) + "]";
    if (!q.is_array() || q.size() != 2) TrackError(file, f, q.dump(), "must be a point [x, y]");
    p.x.emplace_back(number(q[0], f + "[0]"), number(q[1], f + "[1]"));
  }
  auto numbers = [&](const char* key, std::vector<double>* out) {
    if (!doc.contains(key)) return;
    if (!doc[key].is_array()) TrackError(file, key, doc[key].dump(), "must be an array of numbers");
    for (std::size_t i = 0; i < doc[key].size(); ++i)
      out->push_back(number(doc[key][i], std::string(key) + "[" + std::to_string(i) + "]"));
  };
  numbers("sigma", &p.sigma);
  numbers("spin", &p.spin);
  numbers("sigma_spin", &p.sigma_spin);
  numbers("sigma_orientation", &p.sigma_orientation);
  numbers("sigma_body_rate", &p.sigma_body_rate);
  // Rows of k numbers: the quaternions [w, x, y, z] and the body rates [wx, wy, wz].
  auto tuples = [&](const char* key, int k, const char* what, auto push) {
    if (!doc.contains(key)) return;
    if (!doc[key].is_array()) TrackError(file, key, doc[key].dump(), std::string("must be an array of ") + what);
    for (std::size_t i = 0; i < doc[key].size(); ++i) {
      const json& v = doc[key][i];
      const std::string f = std::string(key) + "[" + std::to_string(i) + "]";
      if (!v.is_array() || v.size() != static_cast<std::size_t>(k))
        TrackError(file, f, v.dump(), std::string("must be ") + what);
      double c[4] = {0, 0, 0, 0};
      for (int m = 0; m < k; ++m) c[m] = number(v[static_cast<std::size_t>(m)], f + "[" + std::to_string(m) + "]");
      push(c);
    }
  };
  tuples("orientation", 4, "a unit quaternion [w, x, y, z]", [&](const double* c) {
    p.orientation.emplace_back(c[0], c[1], c[2], c[3]);
  });
  tuples(
      "body_rate", 3, "a body rate [wx, wy, wz]", [&](const double* c) { p.body_rate.emplace_back(c[0], c[1], c[2]); });
  if (doc.contains("impulse_times")) {
    const json& times = doc["impulse_times"];
    if (!times.is_array()) TrackError(file, "impulse_times", times.dump(), "must be an array of times");
    for (std::size_t i = 0; i < times.size(); ++i)
      p.impulse_times.push_back(number(times[i], "impulse_times[" + std::to_string(i) + "]"));
  }
  return p;
}

/// The track and its impulse times (the JSON's impulse_times or --impulses, not both).
IdentifyProblem ReadTrack(const std::string& file, const IdentifyCliOptions& o) {
  const std::string text = ReadInputText(file);
  const auto first = text.find_first_not_of(" \t\r\n");
  IdentifyProblem p = first != std::string::npos && (text[first] == '{' || text[first] == '[')
                          ? ReadTrackJson(file, text)
                          : ReadTrackCsv(file, text);
  if (o.impulses_opt->count() > 0) {
    if (!p.impulse_times.empty())
      ThrowInvalidInput(CommandLineField("--impulses"),
                        "(set)",
                        "the track file " + file + " has impulse_times already: give them once");
    p.impulse_times = o.impulses;
  }
  // The library names its field ("impulse_times[0]: value ..."): times from --impulses are named so.
  const std::string error = p.Validate(), times = "impulse_times";
  if (!error.empty() && error.rfind(times, 0) == 0 && o.impulses_opt->count() > 0)
    throw std::invalid_argument(CommandLineField("--impulses") + error.substr(times.size()));
  if (!error.empty()) throw std::invalid_argument(file + ": " + error);
  return p;
}

// ------------------------------------------------------------------ output

Json FiniteOrNull(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

/// The index of the first delta psi in standard_errors (after chi when the frame is fitted).
std::size_t FirstImpulse(const IdentifySummary& s) { return s.frame_fitted ? 8 : 7; }

Json ErrorsJson(const IdentifySummary& s) {
  Json j = Json::object();
  for (int i = 0; i < 5; ++i)
    j[kIdentifyParameterNames[i]] = FiniteOrNull(s.standard_errors[static_cast<std::size_t>(i)]);
  j["x0"] = Json::array({FiniteOrNull(s.standard_errors[5]), FiniteOrNull(s.standard_errors[6])});
  if (s.frame_fitted) j["chi"] = FiniteOrNull(s.standard_errors[7]);
  if (!s.delta_psi.empty()) {
    j["delta_psi"] = Json::array();
    for (std::size_t k = 0; k < s.delta_psi.size(); ++k)
      j["delta_psi"].push_back(FiniteOrNull(s.standard_errors[FirstImpulse(s) + k]));
  }
  return j;
}

Json CorrelationJson(const IdentifySummary& s) {
  Json rows = Json::array();
  for (Eigen::Index i = 0; i < s.correlation.rows(); ++i) {
    Json row = Json::array();
    for (Eigen::Index k = 0; k < s.correlation.cols(); ++k) row.push_back(FiniteOrNull(s.correlation(i, k)));
    rows.push_back(row);
  }
  return rows;
}

/// Each impulse: its time, the fitted delta psi with its standard error, and the state after it.
Json ImpulsesJson(const IdentifySummary& s) {
  Json impulses = Json::array();
  for (std::size_t k = 0; k < s.delta_psi.size(); ++k) {
    const IdentifiedFlight& after = s.flights[k + 1];
    impulses.push_back(Json{{"t", s.impulse_times[k]},
                            {"delta_psi", s.delta_psi[k]},
                            {"delta_psi_error", FiniteOrNull(s.standard_errors[FirstImpulse(s) + k])},
                            {"angles_after", ToJson(after.angles)},
                            {"x", ToJson(after.x)}});
  }
  return impulses;
}

Json FitJson(const IdentifySummary& s) {
  Json j{{"t_ref", s.t_ref},
         {"lambda", s.lambda},
         {"mu", s.mu},
         {"angles", ToJson(s.angles)},
         {"x0", ToJson(s.x0)},
         {"period", s.period},
         {"standard_errors", ErrorsJson(s)}};
  if (std::isfinite(s.lambda_low) || std::isinf(s.lambda_high))
    j["lambda_interval"] = Json{{"low", s.lambda_low},
                                {"high", FiniteOrNull(s.lambda_high)},
                                {"closed", s.lambda_low > 0 && std::isfinite(s.lambda_high)},
                                {"confidence", 0.95},
                                {"method", s.interval_method}};
  j["identifiability"] = Json{{"lambda_identified", s.lambda_identified},
                              {"lambda_relative_error", FiniteOrNull(s.lambda_relative_error)},
                              {"scaled_condition", s.scaled_condition},
                              {"path_deviation", s.path_deviation},
                              {"straight_path", s.straight_path},
                              {"unidentified", s.unidentified}};
  if (!s.delta_psi.empty()) j["impulses"] = ImpulsesJson(s);
  if (s.frame_fitted)
    j["orientation"] = Json::array({s.orientation[0], s.orientation[1], s.orientation[2], s.orientation[3]});
  j["correlation"] = CorrelationJson(s);
  j["parameters"] = s.parameters;
  return j;
}

Json ResidualsJson(const IdentifySummary& s) {
  Json j{{"samples", s.samples},
         {"rms", s.rms_residual},
         {"max", s.max_residual},
         {"chi_square", s.chi_square},
         {"sigma", s.sigma},
         {"sigma_estimated", s.sigma_estimated},
         {"track_spread", s.track_spread}};
  if (!s.fitted_spin.empty()) j["spin"] = Json{{"rms", s.spin_rms_residual}, {"max", s.spin_max_residual}};
  if (!s.fitted_orientation.empty())
    j["orientation"] = Json{{"rms", s.orientation_rms_residual}, {"max", s.orientation_max_residual}};
  if (!s.fitted_body_rate.empty())
    j["body_rate"] = Json{{"rms", s.body_rate_rms_residual}, {"max", s.body_rate_max_residual}};
  return j;
}

/// The fitted model as problem-file sections (ball, initial) that plan and steer read.
Json FittedProblemJson(const IdentifySummary& s) {
  Json j{{"ball", Json{{"lambda", s.lambda}}},
         {"initial",
          Json{{"theta", s.angles.theta},
               {"phi", s.angles.phi},
               {"psi", s.angles.psi},
               {"mu", s.mu},
               {"x0", ToJson(s.x0)}}}};
  // With the frame fitted: the orientation at t_ref too (its third column is the fitted axis).
  if (s.frame_fitted)
    j["initial"]["orientation"] =
        Json{{"quaternion", Json::array({s.orientation[0], s.orientation[1], s.orientation[2], s.orientation[3]})}};
  return j;
}

/// Six significant digits for a title.
std::string Short(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

/// The plate view: the measured track (points) and the fitted free motion (line), in radii.
SvgFigure PlateFigure(const IdentifyProblem& track, const IdentifySummary& s, double radius, bool fitted) {
  SvgFigure fig(640, 560);
  fig.Title("plateball identify: " + ToString(s.status) +
            (fitted ? ", lambda = " + Short(s.lambda) + ", mu = " + Short(s.mu) : std::string()));
  // The points first, the fitted line over them: a good fit runs through the cloud.
  const SvgFigure::Style point{"#555555", 1.0, "", "#555555"};
  for (const Eigen::Vector2d& x : track.x) fig.Marker(x / radius, 1.2, point);
  fig.Legend("measured track", point, SvgFigure::Swatch::kPoint);
  if (fitted) {
    // Flight by flight (one without impulses), each from its fitted start to the next impulse.
    std::vector<Eigen::Vector2d> curve;
    constexpr int kCurvePoints = 600;
    for (std::size_t f = 0; f < s.flights.size(); ++f) {
      const IdentifiedFlight& flight = s.flights[f];
      const double end = f + 1 < s.flights.size() ? s.flights[f + 1].t_start : track.t.back();
      const FreeMotion motion = FreeMotion::FromAngles(BallModel::FromLambda(s.lambda), flight.angles, s.mu, flight.x);
      const int points =
          std::max(2, static_cast<int>(kCurvePoints * (end - flight.t_start) / (track.t.back() - track.t.front())));
      for (int i = 0; i <= points; ++i) curve.push_back(motion.PositionAt((end - flight.t_start) * i / points));
    }
    fig.Polyline(curve, {"#1f77b4", 1.2, "", "none"});
    fig.Legend(s.flights.size() > 1 ? "fitted free flights between the impulses" : "fitted free motion",
               {"#1f77b4", 1.2, "", "none"});
  }
  return fig;
}

/// The residual components (measured - fitted, radii) against time.
SvgFigure ResidualFigure(const IdentifyProblem& track, const IdentifySummary& s, double radius) {
  SvgFigure fig(640, 340);
  fig.EqualAspect(false);
  fig.Title("residuals, rms " + Short(s.rms_residual) + " radii");
  fig.AxisLabels("t", "measured - fitted (ball radii)");
  std::vector<Eigen::Vector2d> rx, ry;
  for (std::size_t i = 0; i < track.t.size(); ++i) {
    const Eigen::Vector2d r = track.x[i] / radius - s.fitted[i];
    rx.emplace_back(track.t[i], r.x());
    ry.emplace_back(track.t[i], r.y());
  }
  fig.Polyline({{track.t.front(), 0.0}, {track.t.back(), 0.0}}, {"gray", 1.0, "4,3", "none"});
  fig.Polyline(rx, {"#d62728", 1.0, "", "none"});
  fig.Polyline(ry, {"#2ca02c", 1.0, "", "none"});
  fig.Legend("x residual", {"#d62728", 1.0, "", "none"});
  fig.Legend("y residual", {"#2ca02c", 1.0, "", "none"});
  return fig;
}

/// With orientations: the angle |LogSO3(A_i^T A(t_i))| (rad) against time; with body rates the
/// components of measured - fitted A^T omega.
SvgFigure FrameResidualFigure(const IdentifyProblem& track, const IdentifySummary& s) {
  SvgFigure fig(640, 340);
  fig.EqualAspect(false);
  const bool orientation = !s.fitted_orientation.empty();
  fig.Title(orientation ? "orientation residuals, rms " + Short(s.orientation_rms_residual) + " rad"
                        : "body-rate residuals, rms " + Short(s.body_rate_rms_residual));
  fig.AxisLabels("t",
                 orientation ? "angle between measured and fitted (rad)" : "measured - fitted (rad per time unit)");
  fig.Polyline({{track.t.front(), 0.0}, {track.t.back(), 0.0}}, {"gray", 1.0, "4,3", "none"});
  const char* colours[3] = {"#d62728", "#2ca02c", "#1f77b4"};
  if (orientation) {
    std::vector<Eigen::Vector2d> angle;
    for (std::size_t i = 0; i < track.t.size(); ++i) {
      const Eigen::Vector4d& q = s.fitted_orientation[i];
      angle.emplace_back(track.t[i],
                         RotationAngle(QuaternionToRotation(track.orientation[i]), QuaternionToRotation(q)));
    }
    fig.Polyline(angle, {colours[0], 1.0, "", "none"});
    fig.Legend("orientation residual angle", {colours[0], 1.0, "", "none"});
    return fig;
  }
  for (int c = 0; c < 3; ++c) {
    std::vector<Eigen::Vector2d> r;
    for (std::size_t i = 0; i < track.t.size(); ++i)
      r.emplace_back(track.t[i], track.body_rate[i][c] - s.fitted_body_rate[i][c]);
    fig.Polyline(r, {colours[c], 1.0, "", "none"});
    fig.Legend(std::string("body rate ") + "xyz"[c] + " residual", {colours[c], 1.0, "", "none"});
  }
  return fig;
}

/// The panels stacked in one SVG (each rendered by SvgFigure, nested at its offset).
void WriteFigure(const std::string& path, const IdentifyProblem& track, const IdentifySummary& s, double radius) {
  const bool fitted = !s.fitted.empty() && s.mu > 0;
  std::vector<std::string> panels{PlateFigure(track, s, radius, fitted).Render()};
  if (fitted) panels.push_back(ResidualFigure(track, s, radius).Render());
  if (fitted && (!s.fitted_orientation.empty() || !s.fitted_body_rate.empty()))
    panels.push_back(FrameResidualFigure(track, s).Render());
  double height = 0;
  std::string body;
  for (std::string& panel : panels) {
    // Each panel is a complete <svg width=".." height=".."> element: nest it at y = height.
    const auto h = panel.find("height=\"");
    const double panel_height = std::stod(panel.substr(h + 8));
    panel.replace(0, 4, "<svg y=\"" + Short(height) + "\"");
    body += panel;
    height += panel_height;
  }
  WriteOutput(path,
              "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"" + Short(height) +
                  "\" viewBox=\"0 0 640 " + Short(height) + "\">\n" + body + "</svg>\n");
}

int RunIdentify(const IdentifyCliOptions& o) {
  CheckOutputPaths({{"--out", o.out}, {"--svg", o.svg}}, {{"TRACK", o.track}, {"PROBLEM.json", o.problem}});
  const IdentifyProblem track = ReadTrack(o.track, o);
  Problem p;
  p.source = "(built-in defaults)";
  if (!o.problem.empty()) p = ReadProblemInput(o.problem);
  IdentifyOptions opt;
  opt.integration = {std::max(p.integration.absolute_tolerance, 1e-13),
                     std::max(p.integration.relative_tolerance, 1e-13),
                     p.integration.max_steps};
  if (o.problem.empty()) opt.integration = IdentifyOptions().integration;
  if (p.physical) opt.radius = p.physical->radius;
  if (o.radius_opt->count() > 0) opt.radius = RequirePositiveOption("--radius", o.radius);
  opt.profile_interval = !o.no_profile;
  opt.threads = ThreadsOption(o.threads);
  if (o.guess) {
    if (o.problem.empty())
      ThrowInvalidInput(CommandLineField("--guess"), "(set)", "needs PROBLEM.json (its ball.lambda and initial state)");
    opt.guess = IdentifyGuess{p.model.lambda(), p.mu, p.initial, p.x0 * opt.radius, {}};
  }
  const IdentifySummary s = Identify(track, opt);

  Json doc = HeaderJson("plateball", "identify", p, o.problem, false);
  doc["integration"] = Json{{"absolute_tolerance", opt.integration.absolute_tolerance},
                            {"relative_tolerance", opt.integration.relative_tolerance},
                            {"max_steps", opt.integration.max_steps}};
  doc["options"] = Json{{"radius", opt.radius},
                        {"lambda_min", opt.lambda_min},
                        {"lambda_max", opt.lambda_max},
                        {"max_lambda_relative_error", opt.max_lambda_relative_error},
                        {"profile_interval", opt.profile_interval},
                        {"guess", o.guess}};
  doc["track"] = Json{{"file", o.track},
                      {"samples", track.t.size()},
                      {"t_first", track.t.front()},
                      {"t_last", track.t.back()},
                      {"sigma_given", !track.sigma.empty()},
                      {"spin_given", !track.spin.empty()},
                      {"orientation_given", !track.orientation.empty()},
                      {"body_rate_given", !track.body_rate.empty()},
                      {"impulse_times", track.impulse_times}};
  Append(doc, ResultJson(ToString(s.status), s.IsSolutionUsable(), s.message, s.BriefReport()));
  const bool fitted = s.status == IdentifyStatus::kIdentified || s.status == IdentifyStatus::kLambdaNotIdentified;
  if (fitted) doc["fit"] = FitJson(s);
  if (s.status != IdentifyStatus::kFailed) doc["residuals"] = ResidualsJson(s);
  if (s.IsSolutionUsable()) doc["fitted_problem"] = FittedProblemJson(s);
  doc["starts"] = s.starts;
  doc["iterations"] = s.iterations;
  doc["profile_fits"] = s.profile_fits;
  if (!o.svg.empty()) WriteFigure(o.svg, track, s, opt.radius);
  WriteJson(doc, o.out);
  return fitted ? kExitSuccess : kExitNoSolution;
}

std::function<int()> SetupIdentify(CLI::App& sub) {
  auto o = std::make_shared<IdentifyCliOptions>();
  sub.add_option(
         "TRACK",
         o->track,
         "the track: CSV with a header t,x,y[,sigma][,spin,sigma_spin][,qw,qx,qy,qz[,sigma_orientation]]"
         "[,wx,wy,wz,sigma_body_rate] or JSON {\"t\", \"x\", \"sigma\", \"impulse_times\", \"spin\", \"sigma_spin\", "
         "\"orientation\", \"sigma_orientation\", \"body_rate\", \"sigma_body_rate\"} (\"-\": standard input)")
      ->required();
  sub.add_option("PROBLEM.json",
                 o->problem,
                 "optional problem file: its integration tolerances, ball.physical.radius (a track in metres) and, "
                 "with --guess, its ball.lambda and initial state as the start of the fit");
  sub.add_option("--out", o->out, "write the JSON to this file instead of standard output");
  sub.add_option("--svg", o->svg, "draw the track, the fitted motion and the residuals to this SVG file");
  o->radius_opt = sub.add_option(
      "--radius", o->radius, "the ball's radius in the track's length unit (default 1, or ball.physical.radius)");
  o->impulses_opt = sub.add_option("--impulses",
                                   o->impulses,
                                   "times of known energy-preserving impulses that separate the track's flights, "
                                   "comma-separated (T1,T2,...): one delta psi fitted per impulse")
                        ->delimiter(',');
  sub.add_flag(
      "--guess", o->guess, "start from PROBLEM.json's ball.lambda and initial state instead of the multi-start");
  sub.add_flag("--no-profile", o->no_profile, "skip the profile-likelihood interval of lambda (faster)");
  sub.add_option("--threads",
                 o->threads,
                 "threads for the multi-start and the profile (default: the hardware's; "
                 "results do not depend on it)");
  sub.footer(
      "Fits lambda, mu and the state (angles, contact point) at the track's first time to a measured track of\n"
      "the contact point (docs/identify.md); with --impulses (or the JSON track's impulse_times) the flights\n"
      "between known impulses share lambda and mu, and each impulse's delta psi is fitted. Measured orientations\n"
      "(unit quaternions qw,qx,qy,qz of the body-to-world rotation, norm within 1e-5 of 1) and body angular\n"
      "velocities (wx,wy,wz, an IMU's rates in the body frame) are fitted too and identify lambda even from a\n"
      "short flight. Prints JSON (docs/output_contract.md): status identified |\n"
      "lambda_not_identified | no_fit | failed, the fit with standard errors, the 95% profile interval of\n"
      "lambda, an identifiability report, the residuals and, when identified, fitted_problem: the ball and\n"
      "initial sections of a problem file for plan and steer.\n"
      "Example: plateball identify tests/data/identify_track.csv --svg fit.svg\n"
      "Exit codes: 0 fitted (lambda identified or not), 2 usage, 3 invalid input, 4 no fit or the fit failed,\n"
      "5 unreadable file.");
  return [o] { return RunIdentify(*o); };
}

const CommandRegistrar kRegistrar{
    {"identify", "fit lambda, mu and the initial state to a measured contact-point track (JSON)", SetupIdentify}};

}  // namespace
}  // namespace plateball::tools
