// The JSON problem-file reader and writer (problem_io.h): round trips, one error message format
// for every kind of bad input, the three orientation forms, golden values, robustness.
#include "plateball/problem_io.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "problem_io/field_archive.h"
#include "support/test_support.h"

using namespace plateball;
using nlohmann::json;

namespace {

// Orientations from different forms agree up to the round-off of building them.
constexpr double kOrientationTolerance = 1e-14;

// A valid document with every section filled, the base of the round trip and error cases.
json FullDocument() {
  return json::parse(R"({
    "name": "full",
    "description": "every section",
    "seed": 42,
    "integration": {"absolute_tolerance": 1e-11, "relative_tolerance": 1e-10, "max_steps": 50000},
    "ball": {"physical": {"inertia_1": 0.4, "inertia_3": 0.3, "ball_mass": 1.0, "radius": 1.0, "plate_mass": 0.25}},
    "initial": {"theta": -1.0471975511965976, "phi": 1.5707963267948966, "psi": 0.1, "mu": 1.3,
                "x0": [0.5, -0.25], "orientation": {"quaternion": [0.9, 0.1, -0.3, 0.2]}},
    "simulate": {"t_end": 12.5, "samples": 7},
    "reach": {"targets": [[1, 2], [-3.5, 0.25]], "horizon_periods": 4},
    "plan": {
      "path": {"type": "piecewise", "pieces": [
        {"type": "line", "from": [0, 0], "to": [1, 0]},
        {"type": "circle", "center": [1, 1], "radius": 1, "tau_begin": -1.5707963267948966, "tau_end": 0},
        {"type": "samples", "points": [[2, 1], [2.5, 1.5], [3, 1.25]]},
        {"type": "sine", "from": [3, 1.25], "rotation": 0.3, "length": 2, "amplitude": 0.1, "wavelength": 1}
      ]},
      "partition": {"type": "explicit", "taus": [0, 0.5, 1.5, 2]},
      "energy_changes": [{"index": 1, "factor": 0.5}, {"index": 2, "factor": 2}],
      "converge_n": [4, 8, 16]
    },
    "isoparallel": {"start": [0, 0], "goal": [3, 3],
                    "start_orientation": {"axis_angle": {"axis": [1, 0, 0], "angle": 0.5}},
                    "goal_orientation": {"matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]},
                    "impulses": 24,
                    "solver": {"starts": 10, "length_cap_factor": 2.5, "max_iterations": 60,
                               "tolerance": 1e-10, "threads": 2}},
    "expected": {"length": {"value": 7.25, "tolerance": 1e-6}, "count": {"value": 3, "tolerance": 0}}
  })");
}

json MinimalDocument() {
  return json::parse(R"({"ball": {"lambda": 1.5}, "initial": {"theta": 1, "phi": 0, "psi": 0, "mu": 1}})");
}

void ExpectSamePath(const PathSpec& a, const PathSpec& b) {
  ASSERT_EQ(ToString(a), ToString(b));
  std::visit(
      [&](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        const T& y = std::get<T>(b.shape);
        if constexpr (std::is_same_v<T, LineSpec>) {
          EXPECT_EQ(x.from, y.from);
          EXPECT_EQ(x.to, y.to);
        } else if constexpr (std::is_same_v<T, CircleSpec>) {
          EXPECT_EQ(x.center, y.center);
          EXPECT_EQ(x.radius, y.radius);
        } else if constexpr (std::is_same_v<T, EllipseSpec>) {
          EXPECT_EQ(x.center, y.center);
          EXPECT_EQ(x.semi_axes, y.semi_axes);
          EXPECT_EQ(x.rotation, y.rotation);
        } else if constexpr (std::is_same_v<T, LemniscateSpec>) {
          EXPECT_EQ(x.center, y.center);
          EXPECT_EQ(x.scale, y.scale);
          EXPECT_EQ(x.rotation, y.rotation);
        } else if constexpr (std::is_same_v<T, SineSpec>) {
          EXPECT_EQ(x.from, y.from);
          EXPECT_EQ(x.rotation, y.rotation);
          EXPECT_EQ(x.length, y.length);
          EXPECT_EQ(x.amplitude, y.amplitude);
          EXPECT_EQ(x.wavelength, y.wavelength);
        } else if constexpr (std::is_same_v<T, SamplesSpec>) {
          EXPECT_EQ(x.points, y.points);
        } else {
          ASSERT_EQ(x.pieces.size(), y.pieces.size());
          for (std::size_t i = 0; i < x.pieces.size(); ++i) ExpectSamePath(x.pieces[i], y.pieces[i]);
        }
        if constexpr (std::is_same_v<T, CircleSpec> || std::is_same_v<T, EllipseSpec> ||
                      std::is_same_v<T, LemniscateSpec>) {
          EXPECT_EQ(x.tau_begin, y.tau_begin);
          EXPECT_EQ(x.tau_end, y.tau_end);
        }
      },
      a.shape);
}

// n of a uniform rule, the step count of an explicit one.
int Steps(const PartitionSpec& rule) {
  if (const auto* e = std::get_if<ExplicitTaus>(&rule)) return static_cast<int>(e->taus.size()) - 1;
  if (const auto* u = std::get_if<UniformParameter>(&rule)) return u->n;
  return std::get<UniformArcLength>(rule).n;
}

// Field-by-field, bit-exact equality of two problems (except `source`).
void ExpectSameProblem(const Problem& a, const Problem& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.description, b.description);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.integration.absolute_tolerance, b.integration.absolute_tolerance);
  EXPECT_EQ(a.integration.relative_tolerance, b.integration.relative_tolerance);
  EXPECT_EQ(a.integration.max_steps, b.integration.max_steps);
  EXPECT_EQ(a.model.lambda(), b.model.lambda());
  EXPECT_EQ(a.model.has_inertia(), b.model.has_inertia());
  EXPECT_EQ(a.model.alpha(), b.model.alpha());
  EXPECT_EQ(a.model.beta(), b.model.beta());
  ASSERT_EQ(a.physical.has_value(), b.physical.has_value());
  if (a.physical) {
    EXPECT_EQ(a.physical->inertia_1, b.physical->inertia_1);
    EXPECT_EQ(a.physical->inertia_3, b.physical->inertia_3);
    EXPECT_EQ(a.physical->ball_mass, b.physical->ball_mass);
    EXPECT_EQ(a.physical->radius, b.physical->radius);
    EXPECT_EQ(a.physical->plate_mass, b.physical->plate_mass);
  }
  EXPECT_EQ(a.initial.theta, b.initial.theta);
  EXPECT_EQ(a.initial.phi, b.initial.phi);
  EXPECT_EQ(a.initial.psi, b.initial.psi);
  EXPECT_EQ(a.mu, b.mu);
  EXPECT_EQ(a.x0, b.x0);
  EXPECT_EQ(a.A0, b.A0);
  ASSERT_EQ(a.simulate.has_value(), b.simulate.has_value());
  if (a.simulate) {
    EXPECT_EQ(a.simulate->t_end, b.simulate->t_end);
    EXPECT_EQ(a.simulate->samples, b.simulate->samples);
  }
  ASSERT_EQ(a.reach.has_value(), b.reach.has_value());
  if (a.reach) {
    EXPECT_EQ(a.reach->targets, b.reach->targets);
    EXPECT_EQ(a.reach->horizon_periods, b.reach->horizon_periods);
  }
  ASSERT_EQ(a.plan.has_value(), b.plan.has_value());
  if (a.plan) {
    ExpectSamePath(a.plan->path, b.plan->path);
    EXPECT_EQ(ToString(a.plan->partition), ToString(b.plan->partition));
    EXPECT_EQ(Steps(a.plan->partition), Steps(b.plan->partition));
    if (const auto* e = std::get_if<ExplicitTaus>(&a.plan->partition)) {
      EXPECT_EQ(e->taus, std::get<ExplicitTaus>(b.plan->partition).taus);
    }
    ASSERT_EQ(a.plan->energy_changes.size(), b.plan->energy_changes.size());
    for (std::size_t i = 0; i < a.plan->energy_changes.size(); ++i) {
      EXPECT_EQ(a.plan->energy_changes[i].index, b.plan->energy_changes[i].index);
      EXPECT_EQ(a.plan->energy_changes[i].factor, b.plan->energy_changes[i].factor);
    }
    EXPECT_EQ(a.plan->converge_n, b.plan->converge_n);
  }
  ASSERT_EQ(a.isoparallel.has_value(), b.isoparallel.has_value());
  if (a.isoparallel) {
    const IsoparallelTask &x = *a.isoparallel, &y = *b.isoparallel;
    EXPECT_EQ(x.start, y.start);
    EXPECT_EQ(x.goal, y.goal);
    EXPECT_EQ(x.start_orientation, y.start_orientation);
    EXPECT_EQ(x.goal_orientation, y.goal_orientation);
    EXPECT_EQ(x.impulses, y.impulses);
    EXPECT_EQ(x.solver.starts, y.solver.starts);
    EXPECT_EQ(x.solver.length_cap_factor, y.solver.length_cap_factor);
    EXPECT_EQ(x.solver.max_iterations, y.solver.max_iterations);
    EXPECT_EQ(x.solver.tolerance, y.solver.tolerance);
    EXPECT_EQ(x.solver.threads, y.solver.threads);
  }
  ASSERT_EQ(a.steer.has_value(), b.steer.has_value());
  if (a.steer) {
    EXPECT_EQ(a.steer->goal, b.steer->goal);
    EXPECT_EQ(a.steer->goal_orientation, b.steer->goal_orientation);
    EXPECT_EQ(a.steer->impulses, b.steer->impulses);
    EXPECT_EQ(a.steer->start_at_rest, b.steer->start_at_rest);
    EXPECT_EQ(a.steer->stop_at_goal, b.steer->stop_at_goal);
    ASSERT_EQ(a.steer->fewest.has_value(), b.steer->fewest.has_value());
    if (a.steer->fewest) {
      EXPECT_EQ(a.steer->fewest->max_impulses, b.steer->fewest->max_impulses);
      EXPECT_EQ(a.steer->fewest->starts, b.steer->fewest->starts);
      EXPECT_EQ(a.steer->fewest->pareto_counts, b.steer->fewest->pareto_counts);
      EXPECT_EQ(a.steer->fewest->max_total_time, b.steer->fewest->max_total_time);
      EXPECT_EQ(a.steer->fewest->orientation_only, b.steer->fewest->orientation_only);
    }
  }
  ASSERT_EQ(a.expected.size(), b.expected.size());
  for (const auto& [name, v] : a.expected) {
    ASSERT_EQ(b.expected.count(name), 1u) << name;
    EXPECT_EQ(v.value, b.expected.at(name).value);
    EXPECT_EQ(v.tolerance, b.expected.at(name).tolerance);
  }
}

}  // namespace

TEST(ProblemIo, FullDocumentParsesEveryField) {
  const Problem p = ParseProblem(FullDocument().dump(), "full.json");
  EXPECT_EQ(p.source, "full.json");
  EXPECT_EQ(p.name, "full");
  EXPECT_EQ(p.seed, 42u);
  EXPECT_EQ(p.integration.max_steps, 50000);
  ASSERT_TRUE(p.physical.has_value());
  // alpha = I3/I1, beta = (M_ball + 4 M_plate) r^2 / I1 (the plate's kinetic energy; docs/paper_notes.md),
  // lambda = (alpha+beta)/(1+beta).
  const double alpha = 0.3 / 0.4, beta = 2.0 / 0.4;
  EXPECT_DOUBLE_EQ(p.model.lambda(), (alpha + beta) / (1.0 + beta));
  EXPECT_DOUBLE_EQ(p.initial.theta, -M_PI / 3);
  EXPECT_EQ(p.x0, Eigen::Vector2d(0.5, -0.25));
  EXPECT_TRUE(plateball::testing::IsRotationMatrix(p.A0));
  ASSERT_TRUE(p.plan.has_value());
  EXPECT_EQ(std::get<PiecewiseSpec>(p.plan->path.shape).pieces.size(), 4u);
  EXPECT_EQ(Steps(p.plan->partition), 3);  // explicit: one step fewer than the taus
  ASSERT_TRUE(p.isoparallel.has_value());
  EXPECT_TRUE(p.isoparallel->start_orientation.isApprox(
      Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()).toRotationMatrix(), kOrientationTolerance));
  EXPECT_EQ(p.isoparallel->solver.threads, 2);
}

TEST(ProblemIo, WriteThenParseRoundTripsBitExactly) {
  const Problem p = ParseProblem(FullDocument().dump(), "full.json");
  const std::string text = WriteProblemJson(p);
  const Problem q = ParseProblem(text, "written.json");
  ExpectSameProblem(p, q);
  // Canonical: writing the re-read problem gives the same bytes.
  EXPECT_EQ(WriteProblemJson(q), text);
}

TEST(ProblemIo, RoundTripsProblemsBuiltInCode) {
  Problem p;
  p.name = "in code";
  p.model = BallModel::FromAlphaBeta(0.7, 2.5);
  p.initial = {0.1, -2.0, 3.0};
  p.mu = 1.0 / 3.0;
  p.x0 = {M_PI, -M_E};
  p.A0 = Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  p.seed = 18446744073709551615ull;  // largest seed
  PlanTask plan;
  plan.path = PathSpec{LemniscateSpec{{0.1, 0.2}, 2.0, 0.25, 0.0, 2 * M_PI}};
  plan.partition = UniformArcLength{33};
  p.plan = plan;
  ExpectSameProblem(p, ParseProblem(WriteProblemJson(p)));
  p.plan->path = PathSpec{EllipseSpec{{0.1, 0.2}, {2.0, 0.5}, 0.25, 0.0, 2 * M_PI}};
  ExpectSameProblem(p, ParseProblem(WriteProblemJson(p)));
  p.model = BallModel::FromLambda(5.0);
  ExpectSameProblem(p, ParseProblem(WriteProblemJson(p)));
}

TEST(ProblemIo, DefaultsOfOptionalFields) {
  const Problem p = ParseProblem(MinimalDocument().dump(), "min.json");
  EXPECT_EQ(p.model.lambda(), 1.5);
  EXPECT_EQ(p.x0, Eigen::Vector2d::Zero());
  EXPECT_EQ(p.A0, Eigen::Matrix3d::Identity());
  EXPECT_FALSE(p.simulate || p.reach || p.plan || p.isoparallel);
  json d = MinimalDocument();
  d["simulate"] = json::object();
  d["plan"] = json::parse(R"({"path": {"type": "ellipse", "center": [0, 0], "semi_axes": [2, 1],
                                       "tau_begin": 0, "tau_end": 3}})");
  const Problem q = ParseProblem(d.dump(), "defaults.json");
  EXPECT_EQ(q.simulate->t_end, SimulateTask{}.t_end);
  EXPECT_EQ(q.simulate->samples, SimulateTask{}.samples);
  EXPECT_EQ(std::get<EllipseSpec>(q.plan->path.shape).rotation, 0.0);
  EXPECT_EQ(ToString(q.plan->partition), "uniform_parameter");
  EXPECT_EQ(Steps(q.plan->partition), Steps(PartitionSpec{}));
}

TEST(ProblemIo, ThreeOrientationFormsGiveTheSameRotation) {
  // Rotation by 0.7 rad about (1, 2, 3)/sqrt(14): built independently with Eigen's AngleAxis.
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 3).normalized();
  const double angle = 0.7;
  const Eigen::Matrix3d reference = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  const Eigen::Vector3d qv = std::sin(angle / 2) * axis;
  json quaternion = {{"quaternion", {std::cos(angle / 2), qv.x(), qv.y(), qv.z()}}};
  json matrix = {{"matrix", json::array()}};
  for (int i = 0; i < 3; ++i) matrix["matrix"].push_back({reference(i, 0), reference(i, 1), reference(i, 2)});
  json axis_angle = {{"axis_angle", {{"axis", {1, 2, 3}}, {"angle", angle}}}};  // axis normalised by the reader
  std::vector<Eigen::Matrix3d> got;
  for (const json& o : {quaternion, matrix, axis_angle}) {
    json d = MinimalDocument();
    d["initial"]["orientation"] = o;
    d["isoparallel"] = {{"start", {0, 0}}, {"goal", {1, 1}}, {"goal_orientation", o}};
    const Problem p = ParseProblem(d.dump(), "orientation.json");
    EXPECT_TRUE(p.A0.isApprox(reference, kOrientationTolerance)) << o.dump();
    EXPECT_TRUE(p.isoparallel->goal_orientation.isApprox(reference, kOrientationTolerance)) << o.dump();
    EXPECT_TRUE(plateball::testing::IsRotationMatrix(p.A0));
    got.push_back(p.A0);
    EXPECT_TRUE(ParseOrientation(o.dump(), "--orientation").isApprox(reference, kOrientationTolerance));
  }
  EXPECT_LT((got[0] - got[2]).norm(), kOrientationTolerance);
  // A non-unit quaternion is normalised: (2w, 2x, 2y, 2z) is the same rotation.
  json d = MinimalDocument();
  d["initial"]["orientation"] = {{"quaternion", {2 * std::cos(angle / 2), 2 * qv.x(), 2 * qv.y(), 2 * qv.z()}}};
  EXPECT_TRUE(ParseProblem(d.dump()).A0.isApprox(reference, kOrientationTolerance));
}

TEST(ProblemIo, GoldenExpectedValuesAreParsed) {
  const Problem p = ReadProblemFile(plateball::testing::SourcePath("problems/simulate_example.json"));
  ASSERT_EQ(p.expected.count("period"), 1u);
  // The period is 2 pi / sqrt(mu) with mu = 1 in this file.
  EXPECT_DOUBLE_EQ(p.expected.at("period").value, 2 * M_PI / std::sqrt(p.mu));
  EXPECT_EQ(p.expected.at("period").tolerance, 1e-12);
  EXPECT_EQ(p.expected.at("energy").value, 1.0);
  ASSERT_TRUE(p.simulate.has_value());
  EXPECT_EQ(p.simulate->samples, 5);
}

TEST(ProblemIo, EveryRepositoryProblemFileParsesAndRoundTrips) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(plateball::testing::SourcePath("problems"))) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    SCOPED_TRACE(entry.path().string());
    const Problem p = ReadProblemFile(entry.path().string());
    ExpectSameProblem(p, ParseProblem(WriteProblemJson(p)));
  }
  EXPECT_GE(files, 1);
}

// The writer's bytes are a contract (tools write problems back, the byte-identical tool outputs
// compare them): every repository problem file, and the full document, read and written again
// must give the bytes committed in tests/data/written/ (written by the writer before the field
// lists drove it). A mismatch leaves the new text beside the build as NAME.actual.
TEST(ProblemIo, WrittenProblemFilesKeepTheirBytes) {
  std::vector<std::pair<std::string, std::string>> cases;  // (name, written text)
  for (const auto& entry : std::filesystem::directory_iterator(plateball::testing::SourcePath("problems"))) {
    if (entry.path().extension() != ".json") continue;
    cases.emplace_back(entry.path().filename().string(), WriteProblemJson(ReadProblemFile(entry.path().string())));
  }
  cases.emplace_back("full_document.json", WriteProblemJson(ParseProblem(FullDocument().dump(), "full.json")));
  EXPECT_GE(cases.size(), 2u);
  for (const auto& [name, text] : cases) {
    SCOPED_TRACE(name);
    std::ifstream in(plateball::testing::SourcePath("tests/data/written/" + name), std::ios::binary);
    const std::string expected((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text != expected) std::ofstream(name + ".actual", std::ios::binary) << text;
    EXPECT_TRUE(in) << "no committed text for " << name;
    EXPECT_EQ(text, expected);
  }
}

// The sections read by field lists (field_list.h): the schema fragment generated from each list
// is the one committed in schemas/input/problem.schema.json, so the schema cannot drift from the
// reader's keys, types and ranges.
TEST(ProblemIo, FieldListSchemasMatchTheCommittedSchema) {
  using plateball::internal::problem_io::SchemaOfSection;
  std::ifstream in(plateball::testing::SourcePath("schemas/input/problem.schema.json"));
  const json schema = json::parse(in);
  const json& p = schema.at("properties");
  const std::vector<std::pair<std::string, json>> cases = {
      {"integration", p.at("integration")},
      {"simulate", p.at("simulate")},
      {"isoparallel.solver", p.at("isoparallel").at("properties").at("solver")},
      {"steer.fewest", p.at("steer").at("properties").at("fewest")}};
  const std::vector<json> generated = {json::parse(SchemaOfSection<IntegrationOptions>().dump()),
                                       json::parse(SchemaOfSection<SimulateTask>().dump()),
                                       json::parse(SchemaOfSection<IsoparallelOptions>().dump()),
                                       json::parse(SchemaOfSection<SteerTask::Fewest>().dump())};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].first);
    json committed = cases[i].second;
    committed.erase("description");  // the section's own description is not part of its list
    EXPECT_EQ(generated[i], committed) << "generated:\n" << generated[i].dump(2);
  }
}

// The rig section's scalar limits come from RigLimits' field list; its nested shapes, stroke,
// length_unit and pulse_duration are described by hand (with the dependency max_force <->
// pulse_duration), so the list's properties are compared one by one.
TEST(ProblemIo, RigFieldListMatchesTheCommittedSchema) {
  using plateball::internal::problem_io::SchemaOfSection;
  std::ifstream in(plateball::testing::SourcePath("schemas/input/problem.schema.json"));
  const json committed = json::parse(in).at("properties").at("rig");
  const json generated = json::parse(SchemaOfSection<plateball::RigLimits>().dump());
  const std::vector<std::string> by_hand = {"length_unit", "plate", "obstacles", "stroke", "pulse_duration"};
  std::vector<std::string> listed;
  for (const auto& [key, value] : generated.at("properties").items()) {
    listed.push_back(key);
    SCOPED_TRACE(key);
    ASSERT_TRUE(committed.at("properties").contains(key));
    EXPECT_EQ(value, committed.at("properties").at(key)) << "generated:\n" << value.dump(2);
  }
  // json keeps keys sorted: the list's file fields in alphabetical order.
  EXPECT_EQ(listed,
            (std::vector<std::string>{
                "clearance", "max_force", "max_plate_impulse", "max_plate_velocity_change", "min_interval", "tick"}));
  std::vector<std::string> all = listed;
  all.insert(all.end(), by_hand.begin(), by_hand.end());
  EXPECT_EQ(all.size(), committed.at("properties").size()) << "a rig key neither in the list nor read by hand";
  for (const std::string& key : by_hand) EXPECT_TRUE(committed.at("properties").contains(key)) << key;
  EXPECT_EQ(committed.at("additionalProperties"), false);
}

// ------------------------------------------------------------------ errors
struct ErrorCase {
  const char* what;
  std::function<void(json&)> mutate;  // applied to FullDocument() unless `raw` is set
  const char* raw;                    // the whole text, when it is not valid JSON
  const char* field;
  const char* value;
  const char* reason;
};

TEST(ProblemIo, EveryErrorNamesFileFieldAndValue) {
  const std::vector<ErrorCase> cases = {
      {"negative energy", [](json& d) { d["initial"]["mu"] = -1; }, nullptr, "initial.mu", "-1", "must be > 0"},
      {"missing required field",
       [](json& d) { d["initial"].erase("theta"); },
       nullptr,
       "initial.theta",
       "(missing)",
       "required field is missing"},
      {"missing section", [](json& d) { d.erase("ball"); }, nullptr, "ball", "(missing)", "required field is missing"},
      {"unknown top-level key", [](json& d) { d["colour"] = "red"; }, nullptr, "colour", "\"red\"", "unknown key"},
      {"unknown nested key", [](json& d) { d["initial"]["omega"] = 1; }, nullptr, "initial.omega", "1", "unknown key"},
      {"string for number",
       [](json& d) {
         d["ball"] = {{"lambda", "two"}};
       },
       nullptr,
       "ball.lambda",
       "\"two\"",
       "must be a number"},
      {"bool for number",
       [](json& d) { d["initial"]["phi"] = true; },
       nullptr,
       "initial.phi",
       "true",
       "must be a number"},
      {"null for number",
       [](json& d) { d["initial"]["psi"] = nullptr; },
       nullptr,
       "initial.psi",
       "null",
       "must be a number"},
      {"two ball forms",
       [](json& d) {
         d["ball"] = {{"lambda", 1}, {"alpha", 1}, {"beta", 1}};
       },
       nullptr,
       "ball",
       "{object with keys alpha, beta, lambda}",
       "exactly one of"},
      {"beta without alpha",
       [](json& d) {
         d["ball"] = {{"beta", 1}};
       },
       nullptr,
       "ball.alpha",
       "(missing)",
       "required field is missing"},
      {"non-positive lambda",
       [](json& d) {
         d["ball"] = {{"lambda", 0}};
       },
       nullptr,
       "ball.lambda",
       "0",
       "must be > 0"},
      {"I3 above 2 I1",
       [](json& d) { d["ball"]["physical"]["inertia_3"] = 0.9; },
       nullptr,
       "ball.physical.inertia_3",
       "0.9",
       "I3 <= I1 + I2"},
      {"zero radius",
       [](json& d) { d["ball"]["physical"]["radius"] = 0.0; },
       nullptr,
       "ball.physical.radius",
       "0",
       "must be > 0"},
      {"negative mass",
       [](json& d) { d["ball"]["physical"]["plate_mass"] = -0.5; },
       nullptr,
       "ball.physical.plate_mass",
       "-0.5",
       "must be >= 0"},
      {"short vector", [](json& d) { d["initial"]["x0"] = {1}; }, nullptr, "initial.x0", "[1]", "array of 2 numbers"},
      {"vector element type",
       [](json& d) {
         d["reach"]["targets"] = {{1, "a"}};
       },
       nullptr,
       "reach.targets[0][1]",
       "\"a\"",
       "must be a number"},
      {"number overflow",
       nullptr,
       R"({"ball": {"lambda": 1}, "initial": {"theta": 1e400, "phi": 0, "psi": 0, "mu": 1}})",
       "initial.theta",
       "1e400",
       "number overflow parsing '1e400'"},
      {"scaled matrix",
       [](json& d) {
         d["initial"]["orientation"] = {{"matrix", {{2, 0, 0}, {0, 2, 0}, {0, 0, 2}}}};
       },
       nullptr,
       "initial.orientation.matrix",
       "[[2, 0, 0], [0, 2, 0], [0, 0, 2]]",
       "not a rotation matrix to 1e-9"},
      {"reflection",
       [](json& d) {
         d["initial"]["orientation"] = {{"matrix", {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}}}};
       },
       nullptr,
       "initial.orientation.matrix",
       "[[1, 0, 0], [0, 1, 0], [0, 0, -1]]",
       "det R = -1 (a reflection)"},
      {"matrix off by 1e-6",
       [](json& d) {
         d["isoparallel"]["goal_orientation"] = {{"matrix", {{1, 1e-6, 0}, {0, 1, 0}, {0, 0, 1}}}};
       },
       nullptr,
       "isoparallel.goal_orientation.matrix",
       "[[1, 1e-06, 0]",
       "max |R^T R - I| = 1e-06"},
      {"zero quaternion",
       [](json& d) {
         d["initial"]["orientation"] = {{"quaternion", {0, 0, 0, 0}}};
       },
       nullptr,
       "initial.orientation.quaternion",
       "[0, 0, 0, 0]",
       "non-zero quaternion"},
      {"two orientation forms",
       [](json& d) {
         d["initial"]["orientation"]["matrix"] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
       },
       nullptr,
       "initial.orientation",
       "{object with keys matrix, quaternion}",
       "exactly one of"},
      {"zero rotation axis",
       [](json& d) {
         d["initial"]["orientation"] = {{"axis_angle", {{"axis", {0, 0, 0}}, {"angle", 1}}}};
       },
       nullptr,
       "initial.orientation.axis_angle.axis",
       "[0, 0, 0]",
       "non-zero vector"},
      {"zero samples", [](json& d) { d["simulate"]["samples"] = 0; }, nullptr, "simulate.samples", "0", "must be >= 2"},
      {"fractional count",
       [](json& d) { d["simulate"]["samples"] = 2.5; },
       nullptr,
       "simulate.samples",
       "2.5",
       "must be an integer"},
      {"absurd count",
       [](json& d) { d["simulate"]["samples"] = 1e12; },
       nullptr,
       "simulate.samples",
       "1000000000000",
       "must be <= 100000"},
      {"zero tolerance",
       [](json& d) { d["integration"]["absolute_tolerance"] = 0; },
       nullptr,
       "integration.absolute_tolerance",
       "0",
       "must be in [1e-15, 1)"},
      {"negative max_steps",
       [](json& d) { d["integration"]["max_steps"] = -5; },
       nullptr,
       "integration.max_steps",
       "-5",
       "must be >= 1"},
      {"negative seed", [](json& d) { d["seed"] = -3; }, nullptr, "seed", "-3", "non-negative integer"},
      {"string name", [](json& d) { d["name"] = 5; }, nullptr, "name", "5", "must be a string"},
      {"unknown path type",
       [](json& d) {
         d["plan"]["path"] = {{"type", "spiral"}};
       },
       nullptr,
       "plan.path.type",
       "\"spiral\"",
       "unknown path type"},
      {"field of another path type",
       [](json& d) { d["plan"]["path"]["pieces"][0]["radius"] = 1; },
       nullptr,
       "plan.path.pieces[0].radius",
       "1",
       "unknown key (allowed here: type, from, to)"},
      {"missing path field",
       [](json& d) { d["plan"]["path"]["pieces"][1].erase("radius"); },
       nullptr,
       "plan.path.pieces[1].radius",
       "(missing)",
       "required field is missing"},
      {"gap between pieces",
       [](json& d) {
         d["plan"]["path"]["pieces"][0]["to"] = {1, 0.5};
       },
       nullptr,
       "plan.path.pieces[1]",
       "[1, 0]",
       "must share end points"},
      {"repeated sample",
       [](json& d) {
         d["plan"]["path"]["pieces"][2]["points"][1] = {2, 1};
       },
       nullptr,
       "plan.path.pieces[2].points[1]",
       "[2, 1]",
       "repeats the previous point"},
      {"zero-length line",
       [](json& d) {
         d["plan"]["path"] = {{"type", "line"}, {"from", {1, 1}}, {"to", {1, 1}}};
       },
       nullptr,
       "plan.path.to",
       "[1, 1]",
       "length 0"},
      {"empty arc",
       [](json& d) { d["plan"]["path"]["pieces"][1]["tau_end"] = -1.5707963267948966; },
       nullptr,
       "plan.path.pieces[1].tau_end",
       "-1.5707963267948966",
       "must differ from tau_begin"},
      {"non-increasing taus",
       [](json& d) {
         d["plan"]["partition"]["taus"] = {0, 1, 1, 2};
       },
       nullptr,
       "plan.partition.taus[2]",
       "1",
       "strictly increasing"},
      {"unknown partition",
       [](json& d) {
         d["plan"]["partition"] = {{"type", "random"}};
       },
       nullptr,
       "plan.partition.type",
       "\"random\"",
       "unknown partition type"},
      {"zero energy factor",
       [](json& d) { d["plan"]["energy_changes"][0]["factor"] = 0; },
       nullptr,
       "plan.energy_changes[0].factor",
       "0",
       "must be > 0"},
      {"zero in converge_n",
       [](json& d) {
         d["plan"]["converge_n"] = {4, 0};
       },
       nullptr,
       "plan.converge_n[1]",
       "0",
       "must be >= 1"},
      {"no targets",
       [](json& d) { d["reach"]["targets"] = json::array(); },
       nullptr,
       "reach.targets",
       "[]",
       "at least 1 element"},
      {"negative horizon",
       [](json& d) { d["reach"]["horizon_periods"] = -2; },
       nullptr,
       "reach.horizon_periods",
       "-2",
       "must be in (0, 100]"},
      {"zero threads",
       [](json& d) { d["isoparallel"]["solver"]["threads"] = 0; },
       nullptr,
       "isoparallel.solver.threads",
       "0",
       "must be >= 1"},
      {"negative solver tolerance",
       [](json& d) { d["isoparallel"]["solver"]["tolerance"] = -1e-9; },
       nullptr,
       "isoparallel.solver.tolerance",
       "-1e-09",
       "must be in [1e-15, 1)"},
      {"zero impulses",
       [](json& d) { d["isoparallel"]["impulses"] = 0; },
       nullptr,
       "isoparallel.impulses",
       "0",
       "must be >= 1"},
      {"golden without tolerance",
       [](json& d) { d["expected"]["length"].erase("tolerance"); },
       nullptr,
       "expected.length.tolerance",
       "(missing)",
       "required field is missing"},
      {"section of wrong type",
       [](json& d) {
         d["simulate"] = {1, 2};
       },
       nullptr,
       "simulate",
       "[1, 2]",
       "must be a JSON object"},
      {"malformed JSON",
       nullptr,
       "{\n  \"ball\": {\"lambda\": 1},\n  \"initial\" 5\n}",
       "(document)",
       "",
       "malformed JSON at line 3, column 13"},
      {"empty text", nullptr, "", "(document)", "''", "unexpected end of input"},
      {"duplicate key",
       nullptr,
       R"({"ball": {"lambda": 1}, "initial": {"theta": 1, "phi": 0, "psi": 0, "mu": 1, "mu": 2}})",
       "initial.mu",
       "(duplicate)",
       "more than once"},
      {"array document", nullptr, "[1, 2]", "(document)", "[1, 2]", "must be a JSON object"},
      // Documented ranges (README, "Limits"), each named with the field and the bound.
      {"lambda beyond 1e3",
       [](json& d) {
         d["ball"] = {{"lambda", 1e12}};
       },
       nullptr,
       "ball.lambda",
       "1000000000000",
       "must be in [0.001, 1000]"},
      {"alpha, beta giving a tiny lambda",
       [](json& d) {
         d["ball"] = {{"alpha", 1e-9}, {"beta", 0}};
       },
       nullptr,
       "ball.alpha",
       "1e-09",
       "gives lambda = 1e-09, outside [0.001, 1000]"},
      {"mu 1e50",
       [](json& d) { d["initial"]["mu"] = 1e50; },
       nullptr,
       "initial.mu",
       "1e+50",
       "must be in [1e-12, 1e+12]"},
      {"finite denormal mu",
       [](json& d) { d["initial"]["mu"] = 1e-310; },
       nullptr,
       "initial.mu",
       "1e-310",
       "must be in [1e-12, 1e+12]"},
      {"tolerance 1e-300",
       [](json& d) { d["integration"]["absolute_tolerance"] = 1e-300; },
       nullptr,
       "integration.absolute_tolerance",
       "1e-300",
       "must be in [1e-15, 1)"},
      {"coordinate 1e155",
       [](json& d) {
         d["isoparallel"]["start"] = {1e155, 1e155};
       },
       nullptr,
       "isoparallel.start[0]",
       "1e+155",
       "|coordinate| must be <= 1e+06"},
      {"target beyond the plate",
       [](json& d) {
         d["reach"]["targets"] = {{0, -2e6}};
       },
       nullptr,
       "reach.targets[0][1]",
       "-2000000",
       "|coordinate| must be <= 1e+06"},
      {"radius beyond the plate",
       [](json& d) { d["plan"]["path"]["pieces"][1]["radius"] = 1e300; },
       nullptr,
       "plan.path.pieces[1].radius",
       "1e+300",
       "|coordinate| must be <= 1e+06"},
      {"goal 100 away",
       [](json& d) {
         d["isoparallel"]["goal"] = {100, 0};
       },
       nullptr,
       "isoparallel.goal",
       "[100, 0]",
       "must be <= 40"},
      {"a million starts",
       [](json& d) { d["isoparallel"]["solver"]["starts"] = 1000000; },
       nullptr,
       "isoparallel.solver.starts",
       "1000000",
       "must be <= 10000"},
      {"length cap 1000",
       [](json& d) { d["isoparallel"]["solver"]["length_cap_factor"] = 1000; },
       nullptr,
       "isoparallel.solver.length_cap_factor",
       "1000",
       "must be in [1, 10]"},
      {"a million impulses",
       [](json& d) { d["isoparallel"]["impulses"] = 1000000; },
       nullptr,
       "isoparallel.impulses",
       "1000000",
       "must be <= 10000"},
      {"threads 1024",
       [](json& d) { d["isoparallel"]["solver"]["threads"] = 1024; },
       nullptr,
       "isoparallel.solver.threads",
       "1024",
       "must be <= 256"},
      {"horizon 1e4",
       [](json& d) { d["reach"]["horizon_periods"] = 1e4; },
       nullptr,
       "reach.horizon_periods",
       "10000",
       "must be in (0, 100]"},
  };
  ASSERT_GE(cases.size(), 20u);
  for (const ErrorCase& c : cases) {
    SCOPED_TRACE(c.what);
    std::string text = c.raw ? std::string(c.raw) : std::string();
    if (!c.raw) {
      json d = FullDocument();
      c.mutate(d);
      text = d.dump();
    }
    try {
      ParseProblem(text, "case.json");
      ADD_FAILURE() << "no error for: " << text;
    } catch (const std::invalid_argument& e) {
      const std::string msg = e.what();
      const std::string head = std::string("case.json: ") + c.field + ": value " + c.value;
      EXPECT_EQ(msg.rfind(head, 0), 0u) << "message: " << msg << "\nexpected to start with: " << head;
      EXPECT_NE(msg.find(c.reason), std::string::npos) << "message: " << msg << "\nexpected reason: " << c.reason;
    }
  }
}

// The rig section (scalar limits by RigLimits' field list, the rest by hand): every key, in
// metres, read and written back in the order plate, obstacles, clearance, stroke, the actuator
// bounds, pulse_duration, min_interval, tick; unset limits are left out.
json RigDocument() {
  json d = FullDocument();
  // A ball of radius 0.02 m (50 ball radii per metre), its inertia scaled with radius^2.
  d["ball"]["physical"] = {
      {"inertia_1", 1.6e-4}, {"inertia_3", 1.2e-4}, {"ball_mass", 1.0}, {"radius", 0.02}, {"plate_mass", 0.25}};
  d["rig"] = json::parse(R"({"length_unit": "m",
      "plate": {"type": "rectangle", "min": [-1, -1], "max": [1, 1]},
      "obstacles": [{"type": "disk", "center": [0.5, 0.5], "radius": 0.1}],
      "clearance": 0.01, "stroke": [0.4, 0.6], "max_plate_velocity_change": 3,
      "max_plate_impulse": 0.2, "max_force": 40, "pulse_duration": 0.005, "min_interval": 0.1, "tick": 0.02})");
  return d;
}

TEST(ProblemIo, RigSectionReadsEveryKeyAndWritesItBackInRadii) {
  const Problem p = ParseProblem(RigDocument().dump(), "rig.json");
  const double per_metre = 1.0 / 0.02;  // lengths scale, times and bounds do not
  EXPECT_DOUBLE_EQ(p.rig.clearance, 0.01 * per_metre);
  ASSERT_TRUE(p.rig.stroke);
  EXPECT_DOUBLE_EQ(p.rig.stroke->x(), 0.4 * per_metre);
  EXPECT_DOUBLE_EQ(p.rig.max_plate_velocity_change, 3.0);
  EXPECT_DOUBLE_EQ(p.rig.max_plate_impulse, 0.2);
  EXPECT_DOUBLE_EQ(p.rig.max_force, 40.0);
  EXPECT_DOUBLE_EQ(p.rig.pulse_duration, 0.005);
  EXPECT_DOUBLE_EQ(p.rig.min_interval, 0.1);
  EXPECT_DOUBLE_EQ(p.rig.tick, 0.02);
  const nlohmann::ordered_json written = nlohmann::ordered_json::parse(WriteProblemJson(p)).at("rig");
  std::vector<std::string> keys;
  for (const auto& [key, value] : written.items()) keys.push_back(key);
  EXPECT_EQ(keys,
            (std::vector<std::string>{"plate",
                                      "obstacles",
                                      "clearance",
                                      "stroke",
                                      "max_plate_velocity_change",
                                      "max_plate_impulse",
                                      "max_force",
                                      "pulse_duration",
                                      "min_interval",
                                      "tick"}));
  EXPECT_DOUBLE_EQ(written.at("clearance").get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(written.at("tick").get<double>(), 0.02);
  // Unset limits are left out; clearance is always written; pulse_duration only with max_force.
  Problem bare = p;
  bare.rig = RigLimits{};
  bare.rig.stroke = Eigen::Vector2d(1, 2);
  bare.rig.pulse_duration = 0.5;  // valid without max_force, but a file has it only with max_force
  keys.clear();
  const nlohmann::ordered_json bare_written = nlohmann::ordered_json::parse(WriteProblemJson(bare));
  for (const auto& [key, value] : bare_written.at("rig").items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"clearance", "stroke"}));
}

TEST(ProblemIo, RigErrorsNameTheirField) {
  const std::vector<ErrorCase> cases = {
      {"negative clearance",
       [](json& d) { d["rig"]["clearance"] = -1; },
       nullptr,
       "rig.clearance",
       "-1",
       "must be >= 0"},
      {"zero tick", [](json& d) { d["rig"]["tick"] = 0; }, nullptr, "rig.tick", "0", "must be > 0"},
      {"negative interval",
       [](json& d) { d["rig"]["min_interval"] = -0.5; },
       nullptr,
       "rig.min_interval",
       "-0.5",
       "must be >= 0"},
      {"string bound",
       [](json& d) { d["rig"]["max_plate_velocity_change"] = "fast"; },
       nullptr,
       "rig.max_plate_velocity_change",
       "\"fast\"",
       "must be a number"},
      {"force without pulse",
       [](json& d) { d["rig"].erase("pulse_duration"); },
       nullptr,
       "rig.pulse_duration",
       "(missing)",
       "required field is missing"},
      {"pulse without force",
       [](json& d) { d["rig"].erase("max_force"); },
       nullptr,
       "rig.pulse_duration",
       "0.005",
       "is used only with max_force (the mean force is |J| / pulse_duration)"},
      {"negative pulse",
       [](json& d) { d["rig"]["pulse_duration"] = -1; },
       nullptr,
       "rig.pulse_duration",
       "-1",
       "must be > 0"},
      {"bad unit",
       [](json& d) { d["rig"]["length_unit"] = "ft"; },
       nullptr,
       "rig.length_unit",
       "\"ft\"",
       "must be \"radius\" or \"m\""},
      {"zero stroke",
       [](json& d) {
         d["rig"]["stroke"] = {0.4, 0};
       },
       nullptr,
       "rig.stroke[1]",
       "0",
       "must be > 0"},
      {"unknown key",
       [](json& d) { d["rig"]["colour"] = 1; },
       nullptr,
       "rig.colour",
       "1",
       "unknown key (allowed here: length_unit, plate, obstacles, clearance, stroke, max_plate_velocity_change, "
       "max_plate_impulse, max_force, pulse_duration, min_interval, tick)"},
      {"impulse without masses",
       [](json& d) {
         d["ball"] = {{"lambda", 1.5}};
         d["rig"].erase("length_unit");
       },
       nullptr,
       "rig.max_plate_impulse",
       "0.2",
       "needs ball.physical (a bare lambda fixes no masses)"},
  };
  for (const ErrorCase& c : cases) {
    SCOPED_TRACE(c.what);
    json d = RigDocument();
    c.mutate(d);
    try {
      ParseProblem(d.dump(), "case.json");
      ADD_FAILURE() << "no error for: " << d.dump();
    } catch (const std::invalid_argument& e) {
      const std::string msg = e.what();
      const std::string head = std::string("case.json: ") + c.field + ": value " + c.value + ": " + c.reason;
      EXPECT_EQ(msg.rfind(head, 0), 0u) << "message: " << msg << "\nexpected to start with: " << head;
    }
  }
}

TEST(ProblemIo, UnreadableFileIsAReadErrorNamingThePath) {
  const std::string missing = "/nonexistent/dir/figure7.json";
  try {
    ReadProblemFile(missing);
    ADD_FAILURE() << "no error";
  } catch (const ProblemFileReadError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(missing + ": (file): value \"" + missing + "\"", 0), 0u) << e.what();
  }
  // A directory is not a problem file either.
  EXPECT_THROW(ReadProblemFile(plateball::testing::SourcePath("problems")), ProblemFileReadError);
}

TEST(ProblemIo, FileErrorsNameTheFileAsGiven) {
  const std::string path = (std::filesystem::temp_directory_path() / "plateball_problem_io_bad.json").string();
  {
    std::ofstream out(path);
    out << R"({"ball": {"lambda": 1}, "initial": {"theta": 1, "phi": 0, "psi": 0, "mu": -1}})";
  }
  try {
    ReadProblemFile(path);
    ADD_FAILURE() << "no error";
  } catch (const ProblemFileReadError&) {
    ADD_FAILURE() << "a content error is not a read error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), path + ": initial.mu: value -1: must be > 0");
  }
  std::filesystem::remove(path);
}

TEST(ProblemIo, WriterRejectsNonFiniteNumbersNamingTheField) {
  Problem p;
  p.mu = std::nan("");
  try {
    WriteProblemJson(p);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("initial.mu: value nan"), std::string::npos) << e.what();
  }
}

TEST(ProblemIo, ArbitraryBytesEitherParseOrThrowInvalidArgument) {
  // Truncations at every byte and seeded random byte edits of a full document: the reader must
  // return or throw std::invalid_argument, never anything else (the fuzz target checks more).
  const std::string base = FullDocument().dump(1);
  std::mt19937 rng(12345);
  std::vector<std::string> inputs;
  for (std::size_t n = 0; n < base.size(); n += 3) inputs.push_back(base.substr(0, n));
  const std::string alphabet = "{}[]:,\"0123456789.-+eE \n\\truefalsnl\x01\xff";
  for (int k = 0; k < 3000; ++k) {
    std::string s = base;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = rng() % s.size();
      switch (rng() % 3) {
        case 0:
          s[at] = alphabet[rng() % alphabet.size()];
          break;
        case 1:
          s.erase(at, 1 + rng() % 8);
          break;
        default:
          s.insert(at, 1, alphabet[rng() % alphabet.size()]);
          break;
      }
      if (s.empty()) s = "{";
    }
    inputs.push_back(s);
  }
  // Deep nesting must not exhaust the stack.
  inputs.push_back(std::string(100000, '[') + std::string(100000, ']'));
  inputs.push_back(R"({"ball": {"lambda": 1}, "initial": )" + std::string(50000, '[') + std::string(50000, ']') + "}");
  int parsed = 0, rejected = 0;
  for (const std::string& s : inputs) {
    try {
      ParseProblem(s, "fuzz.json");
      ++parsed;
    } catch (const std::invalid_argument& e) {
      ++rejected;
      EXPECT_EQ(std::string(e.what()).rfind("fuzz.json: ", 0), 0u) << e.what();
    }
  }
  EXPECT_GT(rejected, 0);
  EXPECT_EQ(parsed + rejected, static_cast<int>(inputs.size()));
}

// The steer section's fewest-impulse fields: parsed, and a bad value names its field.
TEST(ProblemIo, SteerFewestFieldsParseAndNameTheirField) {
  const std::string base = R"({"ball": {"lambda": 2}, "initial": {"theta": 0, "phi": 0, "psi": 0, "mu": 1},
    "steer": {"goal": [3, 3], "start_at_rest": true, "stop_at_goal": true, "fewest": )";
  const Problem p = ParseProblem(
      base +
          R"({"max_impulses": 5, "starts": 8, "pareto_counts": 2, "max_total_time": 20, "orientation_only": true}}})",
      "f.json");
  ASSERT_TRUE(p.steer && p.steer->fewest);
  EXPECT_TRUE(p.steer->start_at_rest);
  EXPECT_TRUE(p.steer->stop_at_goal);
  EXPECT_EQ(p.steer->fewest->max_impulses, 5);
  EXPECT_EQ(p.steer->fewest->starts, 8);
  EXPECT_EQ(p.steer->fewest->pareto_counts, 2);
  EXPECT_EQ(p.steer->fewest->max_total_time, 20.0);
  EXPECT_TRUE(p.steer->fewest->orientation_only);
  using plateball::testing::InvalidArgumentMessage;
  EXPECT_NE(InvalidArgumentMessage([&] {
              ParseProblem(base + R"({"max_impulses": 0}}})", "f.json");
            }).find("steer.fewest.max_impulses"),
            std::string::npos);
  EXPECT_NE(InvalidArgumentMessage([&] {
              ParseProblem(base + R"({"starts": 1e9}}})", "f.json");
            }).find("steer.fewest.starts"),
            std::string::npos);
  EXPECT_NE(InvalidArgumentMessage([&] {
              ParseProblem(base + R"({"max_total_time": -1}}})", "f.json");
            }).find("steer.fewest.max_total_time"),
            std::string::npos);
  EXPECT_NE(InvalidArgumentMessage([&] { ParseProblem(base + R"({"bogus": 1}}})", "f.json"); }).find("bogus"),
            std::string::npos);
}

// Angles beyond 1e15 (no digit left modulo 2 pi) are refused by the reader under the file's field
// names, rather than later by the solvers under their own names ("start.theta") or as a NaN
// orientation ("A0[0]: value -nan").
TEST(ProblemIo, HugeAnglesAreRefusedUnderTheFilesFieldNames) {
  using plateball::testing::InvalidArgumentMessage;
  const std::string ball = R"({"ball": {"lambda": 2}, "initial": )";
  EXPECT_EQ(InvalidArgumentMessage(
                [&] { ParseProblem(ball + R"({"theta": 1e300, "phi": 0, "psi": 0, "mu": 1}})", "f.json"); }),
            "f.json: initial.theta: value 1e+300: an angle beyond 1e15 in magnitude has no significant digits left "
            "modulo 2 pi");
  EXPECT_NE(InvalidArgumentMessage([&] {
              ParseProblem(ball + R"({"theta": 0, "phi": 0, "psi": -2e15, "mu": 1}})", "f.json");
            }).find("f.json: initial.psi: value -2e+15"),
            std::string::npos);
  EXPECT_NE(
      InvalidArgumentMessage([&] {
        ParseProblem(
            ball +
                R"({"theta": 0, "phi": 0, "psi": 0, "mu": 1, "orientation": {"axis_angle": {"axis": [0, 0, 1], "angle": 1e300}}}})",
            "f.json");
      }).find("f.json: initial.orientation.axis_angle.angle: value 1e+300: an angle beyond 1e15"),
      std::string::npos);
  // 1e15 itself is still an angle.
  EXPECT_EQ(InvalidArgumentMessage(
                [&] { ParseProblem(ball + R"({"theta": 0, "phi": 0, "psi": 1e15, "mu": 1}})", "f.json"); }),
            "");
}
