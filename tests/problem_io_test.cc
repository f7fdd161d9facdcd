// The JSON problem-file reader and writer (problem_io.h): round trips, the three orientation forms,
// golden values, the field lists against the committed schema (bad input: problem_io_errors_test.cc).
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
#include "support/problem_documents.h"
#include "support/test_support.h"

using namespace plateball;
using nlohmann::json;
using plateball::testing::FullDocument;
using plateball::testing::MinimalDocument;

namespace {

// Orientations from different forms agree up to the round-off of building them.
constexpr double kOrientationTolerance = 1e-14;

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
