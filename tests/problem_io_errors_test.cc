// The problem-file reader and writer (problem_io.h) on bad input: one error message format naming the
// file, the field and the value for every kind of bad document, and robustness against arbitrary bytes.
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

#include "plateball/problem_io.h"
#include "problem_io/field_archive.h"
#include "support/problem_documents.h"
#include "support/test_support.h"

using namespace plateball;
using nlohmann::json;
using plateball::testing::FullDocument;

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
