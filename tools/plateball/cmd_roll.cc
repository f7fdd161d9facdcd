// `plateball roll`: the reorientation of the ball rolled without sliding or spinning along a
// planar path (rolling.h), as JSON.
#include <cmath>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/command_registry.h"
#include "common/errors.h"
#include "common/exit_codes.h"
#include "common/input_file.h"
#include "common/invalid_input.h"
#include "common/json_output.h"
#include "common/limits.h"
#include "common/number_format.h"
#include "common/output_file.h"
#include "common/problem_options.h"
#include "plateball/path.h"
#include "plateball/problem_io.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"

namespace plateball::tools {
namespace {

struct RollOptions {
  std::string problem_file;
  std::string points;
  std::string samples_file;
  bool segment = false;
  std::string orientation;
  double atol = 0.0, rtol = 0.0;
  std::string out;
  CLI::Option* problem_opt = nullptr;
  CLI::Option* points_opt = nullptr;
  CLI::Option* samples_file_opt = nullptr;
  CLI::Option* orientation_opt = nullptr;
  CLI::Option* atol_opt = nullptr;
  CLI::Option* rtol_opt = nullptr;
};

[[noreturn]] void FileError(const std::string& file,
                            const std::string& field,
                            const std::string& value,
                            const std::string& what) {
  ThrowInvalidInput(file + ": " + field, value, what);
}

// A value as text for a message: compact and at most kMaxValueTextChars characters.
std::string ValueText(const nlohmann::json& j) {
  std::string text = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (text.size() > kMaxValueTextChars) text = text.substr(0, kMaxValueTextChars) + "...";
  return text;
}

// Parses with the nesting depth capped (kMaxJsonDepth) and duplicate keys rejected.
nlohmann::json ParseSamplesJson(const std::string& file, const std::string& text) {
  using nlohmann::json;
  std::vector<std::set<std::string>> keys;  // the keys seen in each open object
  const json::parser_callback_t check = [&](int depth, json::parse_event_t event, json& parsed) {
    if (depth > kMaxJsonDepth)
      FileError(file,
                "(document)",
                "(nested deeper than " + std::to_string(kMaxJsonDepth) + ")",
                "arrays and objects may be nested at most " + std::to_string(kMaxJsonDepth) + " deep");
    if (event == json::parse_event_t::object_start) keys.emplace_back();
    if (event == json::parse_event_t::object_end && !keys.empty()) keys.pop_back();
    if (event == json::parse_event_t::key && !keys.empty() && !keys.back().insert(parsed.get<std::string>()).second)
      FileError(file, parsed.get<std::string>(), "(repeated)", "duplicate key");
    return true;
  };
  try {
    return json::parse(text, check);
  } catch (const json::exception& e) {
    FileError(file, "(document)", "(see message)", std::string("malformed JSON: ") + e.what());
  }
}

// A samples file: {"points": [[x, y], ...]} or a bare array [[x, y], ...].
std::vector<Eigen::Vector2d> ReadSamplesFile(const std::string& file) {
  using nlohmann::json;
  const json doc = ParseSamplesJson(file, ReadInputText(file));
  std::string field = "(document)";
  const json* points = &doc;
  if (doc.is_object()) {
    for (auto it = doc.begin(); it != doc.end(); ++it)
      if (it.key() != "points") FileError(file, it.key(), "(any)", "unknown key (a samples file has only \"points\")");
    const auto it = doc.find("points");
    if (it == doc.end()) FileError(file, "points", "(missing)", "required field is missing");
    points = &*it;
    field = "points";
  }
  if (!points->is_array() || points->size() < 2 || points->size() > kMaxPoints)
    FileError(file,
              field,
              points->is_array() ? "[array of " + std::to_string(points->size()) + "]" : ValueText(*points),
              "must be an array of 2 ... " + std::to_string(kMaxPoints) + " points [x, y]");
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 0; i < points->size(); ++i) {
    const json& p = (*points)[i];
    const std::string f = (field == "(document)" ? std::string() : field) + "[" + std::to_string(i) + "]";
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      FileError(file, f, ValueText(p), "must be an array of 2 numbers [x, y]");
    const Eigen::Vector2d q(p[0].get<double>(), p[1].get<double>());
    if (!q.allFinite()) FileError(file, f, ValueText(p), "must be finite");
    out.push_back(q);
  }
  return out;
}

std::string PointText(const Eigen::Vector2d& p) {
  std::string text = DumpJson(ToJson(p));
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

double PolylineLength(const std::vector<Eigen::Vector2d>& pts) {
  double length = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) length += (pts[i] - pts[i - 1]).norm();
  return length;
}

IntegrationOptions RollIntegration(const RollOptions& o, IntegrationOptions integration) {
  if (o.atol_opt->count() > 0) integration.absolute_tolerance = o.atol;
  if (o.rtol_opt->count() > 0) integration.relative_tolerance = o.rtol;
  // The message names the library's field ("absolute_tolerance: value V: ..."): name the option
  // that gave it (a problem file's tolerances were checked by the reader).
  if (const std::string err = integration.Validate(); !err.empty()) {
    for (const auto& [field, option] : {std::pair<std::string, std::string>{"absolute_tolerance", "--atol"},
                                        std::pair<std::string, std::string>{"relative_tolerance", "--rtol"}})
      if (err.rfind(field + ": ", 0) == 0)
        throw std::invalid_argument(CommandLineField(option) + err.substr(field.size()));
    throw std::invalid_argument(err);
  }
  return integration;
}

// The planned path of a problem file: each smooth piece integrated on its own (the velocity
// may jump between pieces), R = R_n ... R_1.
Json RollAlongProblemPath(const RollOptions& o, const Problem& p, Eigen::Matrix3d* r) {
  if (!p.plan) ThrowInvalidInput(o.problem_file + ": plan.path", "(missing)", "roll needs a problem with a plan.path");
  const IntegrationOptions integration = RollIntegration(o, p.integration);
  const Path path = PathFromSpec(p.plan->path, p.source + ": plan.path");
  *r = Eigen::Matrix3d::Identity();
  for (const SmoothCurve& piece : path.pieces()) {
    const PlanarVelocity velocity = [&piece](double tau) { return piece.Derivative(tau); };
    *r = ProjectToSO3(RollingReorientation(velocity, piece.Begin(), piece.End(), {}, integration) * *r);
  }
  return Json{{"source", o.problem_file},
              {"mode", "plan.path"},
              {"type", ToString(p.plan->path)},
              {"pieces", path.PieceCount()},
              {"start", ToJson(path.StartPoint())},
              {"end", ToJson(path.EndPoint())},
              {"length", path.Length()}};
}

Json RollThroughPoints(const RollOptions& o, Eigen::Matrix3d* r) {
  const bool from_points = o.points_opt->count() > 0;
  std::vector<Eigen::Vector2d> points =
      from_points ? ParsePointsOption("--points", o.points, 2) : ReadSamplesFile(o.samples_file);
  for (std::size_t i = 1; i < points.size(); ++i) {
    const std::string field = (from_points ? std::string(kCommandLine) + ": --points" : o.samples_file + ": points") +
                              "[" + std::to_string(i) + "]";
    if (points[i] == points[i - 1])
      ThrowInvalidInput(field, PointText(points[i]), "repeats the previous point (consecutive points must differ)");
    // Chord lengths are squared on the way (spline knots): they must stay finite.
    if (!std::isfinite((points[i] - points[i - 1]).squaredNorm()))
      ThrowInvalidInput(
          field, PointText(points[i]), "too far from the previous point (the squared distance overflows a double)");
  }
  if (!std::isfinite(PolylineLength(points)))
    ThrowInvalidInput(from_points ? CommandLineField("--points") : o.samples_file + ": points",
                      "[array of " + std::to_string(points.size()) + "]",
                      "the path length overflows a double");
  const IntegrationOptions integration = RollIntegration(o, IntegrationOptions{});
  *r = o.segment ? RollAlongPolyline(points) : RollAlongSamples(points, integration);
  return Json{{"source", from_points ? std::string("--points") : o.samples_file},
              {"mode", o.segment ? "polyline" : "spline"},
              {"points", points.size()},
              {"start", ToJson(points.front())},
              {"end", ToJson(points.back())},
              {"polyline_length", PolylineLength(points)}};
}

int RunRoll(const RollOptions& o) {
  CheckOutputPaths({{"--out", o.out}}, {{"PROBLEM.json", o.problem_file}, {"--samples-file", o.samples_file}});
  const int sources =
      int(o.problem_opt->count() > 0) + int(o.points_opt->count() > 0) + int(o.samples_file_opt->count() > 0);
  if (sources != 1)
    ThrowInvalidInput(CommandLineField("PROBLEM.json/--points/--samples-file"),
                      "(" + std::to_string(sources) + " given)",
                      "give exactly one path");
  if (o.segment && o.problem_opt->count() > 0)
    ThrowInvalidInput(
        CommandLineField("--segment"), "(set)", "only for --points or --samples-file, not a problem's plan.path");
  Eigen::Matrix3d r;
  const bool from_problem = o.problem_opt->count() > 0;
  Problem p;
  if (from_problem)
    p = ReadProblemInput(o.problem_file);
  else
    p.source = "(command line)";
  const Json path = from_problem ? RollAlongProblemPath(o, p, &r) : RollThroughPoints(o, &r);
  p.integration = RollIntegration(o, from_problem ? p.integration : IntegrationOptions{});
  // The reorientation does not depend on the ball: the header has no model.
  Json doc = HeaderJson("plateball", "roll", p, o.problem_file, false);
  doc["path"] = path;
  doc["reorientation"] = RotationToJson(r);
  if (o.orientation_opt->count() > 0) {
    const Eigen::Matrix3d a0 = ParseOrientation(o.orientation, "--orientation", kCommandLine);
    doc["orientation_initial"] = ToJson(a0);
    doc["orientation_final"] = ToJson(Eigen::Matrix3d(r * a0));
  }
  WriteJson(doc, o.out);
  return kExitSuccess;
}

std::function<int()> SetupRoll(CLI::App& sub) {
  auto o = std::make_shared<RollOptions>();
  o->problem_opt = sub.add_option(
      "problem",
      o->problem_file,
      "a problem file whose plan.path is rolled along (each smooth piece exactly; \"-\": standard input)");
  o->points_opt = sub.add_option("--points",
                                 o->points,
                                 "the path through the points \"X1,Y1;X2,Y2;...\" (or separated by spaces; >= 2; a "
                                 "natural C^2 spline unless --segment)");
  o->samples_file_opt =
      sub.add_option("--samples-file",
                     o->samples_file,
                     "the path through the points of a JSON file {\"points\": [[x, y], ...]} (\"-\": standard input)");
  sub.add_flag("--segment", o->segment, "roll along the straight segments between the points (a polyline; exact)");
  o->orientation_opt =
      sub.add_option("--orientation",
                     o->orientation,
                     "initial orientation (JSON, as in problem files); adds the final orientation R A0");
  o->atol_opt =
      sub.add_option("--atol", o->atol, "absolute tolerance of the rolling integration (spline paths and plan.path)");
  o->rtol_opt =
      sub.add_option("--rtol", o->rtol, "relative tolerance of the rolling integration (spline paths and plan.path)");
  sub.add_option("--out", o->out, "write the JSON to this file instead of standard output");
  sub.footer(
      "Prints JSON (docs/output_contract.md): the reorientation R = A(end) A(start)^-1 of the ball (radius 1)\n"
      "rolled along the path: matrix, rotation vector w (R = exp(hat w), |w| <= pi), angle |w| and axis. A straight "
      "segment of length L\n"
      "in the direction d gives the rotation by L about e3 x d.\n"
      "Example: plateball roll --segment --points \"0,0;1.2,1.6\"\n"
      "         plateball roll --points \"0,0;1,0.5;2,0;3,-0.5\"\n"
      "         plateball roll PROBLEM.json     (its plan.path)\n"
      "Exit codes: 0 ok, 2 usage, 3 invalid input, 5 unreadable file.");
  return [o] { return RunRoll(*o); };
}

const CommandRegistrar kRegistrar{
    {"roll",
     "reorientation of the ball rolled along a planar path (points, polyline, samples file or plan.path) as JSON",
     SetupRoll}};

}  // namespace
}  // namespace plateball::tools
