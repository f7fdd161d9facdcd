// The shared helpers of the command-line tools (tools/common): exit-code mapping, JSON output,
// option parsing and problem overrides, the number formatter, output files, the plan layout.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "common/command_line.h"
#include "common/errors.h"
#include "common/exit_codes.h"
#include "common/invalid_input.h"
#include "common/json_output.h"
#include "common/number_format.h"
#include "common/output_file.h"
#include "common/plan_json.h"
#include "common/problem_options.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"

using namespace plateball;
using namespace plateball::tools;

namespace {
int CodeFor(const std::function<void()>& thrower, std::string* message = nullptr) {
  std::ostringstream err;
  const int code = RunWithExitCodes(
      "tool",
      [&] {
        thrower();
        return kExitSuccess;
      },
      err);
  if (message) *message = err.str();
  return code;
}
}  // namespace

TEST(ToolErrors, ExceptionsMapToTheDocumentedExitCodes) {
  std::string message;
  EXPECT_EQ(CodeFor([] { throw std::invalid_argument("f.json: initial.mu: value -1: must be > 0"); }, &message),
            kExitBadInput);
  EXPECT_EQ(message, "tool: invalid input: f.json: initial.mu: value -1: must be > 0\n");
  EXPECT_EQ(CodeFor([] { throw ProblemFileReadError("x.json: cannot open"); }), kExitIoError);
  EXPECT_EQ(CodeFor([] { throw IoError("out.json: cannot open the file for writing"); }), kExitIoError);
  EXPECT_EQ(CodeFor([] { throw std::runtime_error("integration exceeded max_steps"); }), kExitNoSolution);
  EXPECT_EQ(CodeFor([] { throw std::logic_error("bug"); }), kExitInternalError);
  EXPECT_EQ(CodeFor([] { throw 42; }), kExitInternalError);
  EXPECT_EQ(CodeFor([] {}), kExitSuccess);
}

// The tools' one invalid-input helper writes the library's format and maps to exit code 3.
TEST(ToolErrors, InvalidInputHasTheStandardFormatAndExitCode) {
  std::string message;
  EXPECT_EQ(CodeFor([] { ThrowInvalidInput(CommandLineField("--samples"), "0", "must be >= 2"); }, &message),
            kExitBadInput);
  EXPECT_EQ(message, "tool: invalid input: command line: --samples: value 0: must be >= 2\n");
  EXPECT_EQ(CodeFor([] { ThrowInvalidInput("r.json: options.trials", "-5", "must be an integer in [1, 1000000]"); },
                    &message),
            kExitBadInput);
  EXPECT_EQ(message, "tool: invalid input: r.json: options.trials: value -5: must be an integer in [1, 1000000]\n");
}

TEST(JsonOutput, DoublesReadBackBitExactly) {
  const double values[] = {0.1,
                           1.0 / 3.0,
                           M_PI,
                           -2.5e-300,
                           std::numeric_limits<double>::denorm_min(),
                           std::numeric_limits<double>::max(),
                           -0.0,
                           123456789.123456789};
  Json doc = Json::array();
  for (double v : values) doc.push_back(v);
  const nlohmann::json back = nlohmann::json::parse(DumpJson(Json{{"v", doc}}));
  for (std::size_t i = 0; i < std::size(values); ++i) {
    const double got = back["v"][i].get<double>();
    EXPECT_EQ(std::memcmp(&got, &values[i], sizeof got), 0) << i << ": " << got;
  }
}

TEST(JsonOutput, NonFiniteNumbersAreRejectedNamingThePath) {
  Json doc{{"samples", Json::array({Json{{"t", 0.0}}, Json{{"t", std::nan("")}}})}};
  try {
    DumpJson(doc);
    ADD_FAILURE() << "no error";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("samples[1].t"), std::string::npos) << e.what();
  }
}

TEST(JsonOutput, VectorsAndMatricesAreOneLineAndStillJson) {
  Json doc{{"x", ToJson(Eigen::Vector2d(1.5, -2))}, {"A", ToJson(Eigen::Matrix3d::Identity().eval())}};
  const std::string text = DumpJson(doc);
  EXPECT_NE(text.find("\"x\": [1.5, -2.0]"), std::string::npos) << text;
  EXPECT_NE(text.find("\"A\": [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]"), std::string::npos) << text;
  EXPECT_EQ(nlohmann::json::parse(text)["A"][2][2].get<double>(), 1.0);
}

TEST(JsonOutput, RotationHasVectorAngleAndAxis) {
  // Rotation by 0.5 about e2: rotation vector (0, 0.5, 0).
  const Json r = RotationToJson(ExpSO3(Eigen::Vector3d(0, 0.5, 0)));
  EXPECT_NEAR(r["angle"].get<double>(), 0.5, 1e-15);
  EXPECT_NEAR(r["axis"][1].get<double>(), 1.0, 1e-15);
  const Json identity = RotationToJson(Eigen::Matrix3d::Identity());
  EXPECT_EQ(identity["angle"].get<double>(), 0.0);
  EXPECT_FALSE(identity.contains("axis"));  // no axis for the identity
}

TEST(ToolOptions, PointsAcceptSemicolonsAndSpaces) {
  const auto a = ParsePointsOption("--points", "0,0;1.5,-2; 3,4e-1", 2);
  const auto b = ParsePointsOption("--points", "0,0 1.5,-2\t3,4e-1;", 2);
  ASSERT_EQ(a.size(), 3u);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a[2], Eigen::Vector2d(3, 0.4));
}

TEST(ToolOptions, BadValuesNameTheOptionAndValue) {
  struct Case {
    std::function<void()> call;
    const char* message;
  };
  const Case cases[] = {
      {[] { ParsePointsOption("--points", "0,0", 2); }, "command line: --points: value \"0,0\": must give at least 2"},
      {[] { ParsePointsOption("--points", "0,0;1,x", 2); }, "command line: --points[1]: value \"1,x\": must be two"},
      {[] { ParsePointOption("--x0", "1,inf"); }, "command line: --x0: value \"1,inf\": must be two finite numbers"},
      {[] { ParsePointOption("--x0", "1e999,0"); }, "command line: --x0: value \"1e999,0\""},
      {[] { RequirePositiveOption("--mu", -1); }, "command line: --mu: value -1: must be a finite number > 0"},
      {[] { RequireFiniteOption("--theta", INFINITY); }, "command line: --theta: value inf: must be a finite number"},
      {[] { RequireIntegerInRange("--samples", 1, 2, 10); }, "command line: --samples: value 1: must be >= 2"},
  };
  for (const Case& c : cases) {
    try {
      c.call();
      ADD_FAILURE() << "no error for " << c.message;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(c.message, 0), 0u) << e.what();
    }
  }
}

TEST(ToolOptions, OverridesApplyOnTopOfTheDefaultsAndAreValidated) {
  CLI::App app;
  ProblemOptions options;
  options.Add(app);
  app.parse(
      "--lambda 2 --mu 4 --x0 1,-2 --seed 18446744073709551615 --orientation "
      "{\"axis_angle\":{\"axis\":[0,0,1],\"angle\":0.5}}",
      false);
  const Problem p = options.Load();
  EXPECT_EQ(p.model.lambda(), 2.0);
  EXPECT_EQ(p.mu, 4.0);
  EXPECT_EQ(p.x0, Eigen::Vector2d(1, -2));
  EXPECT_EQ(p.seed, 18446744073709551615ull);
  EXPECT_LT((p.A0 - ExpSO3(Eigen::Vector3d(0, 0, 0.5))).norm(), 1e-15);
  EXPECT_EQ(p.initial.phi, Problem{}.initial.phi);  // not overridden

  CLI::App app2;
  ProblemOptions bad;
  bad.Add(app2);
  app2.parse("--atol 1e-16 --rtol 1e-16", false);
  // Each tolerance alone is in (0, 1); the combination is rejected like in a file.
  EXPECT_THROW(bad.Load(), std::invalid_argument);
}

TEST(NumberFormat, ShortestTextReadsBackBitExactly) {
  EXPECT_EQ(FormatNumber(0.1), "0.1");
  EXPECT_EQ(FormatNumber(-3), "-3");
  EXPECT_EQ(FormatNumber(1e200), "1e+200");
  EXPECT_EQ(FormatNumber(INFINITY), "inf");
  // 17 digits would print 0.10000000000000001; every value reads back to the same double.
  for (double v : {0.1, 1.0 / 3.0, 2.0 / 3.0 * 1e-300, 6.02214076e23, std::nextafter(1.0, 2.0), 5e-324}) {
    const std::string text = FormatNumber(v);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), v) << text;
    EXPECT_LE(text.size(), 24u) << text;
  }
}

namespace {
std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
std::string TempDir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}
}  // namespace

TEST(OutputFile, ReplacesTheFileAndLeavesNoTemporary) {
  const std::string dir = TempDir("plateball_output_file");
  const std::string path = dir + "/out.json";
  WriteOutput(path, "first\n");
  WriteOutput(path, "second\n");
  EXPECT_EQ(ReadAll(path), "second\n");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator{}), 1);
  // A path under a plain file cannot be created: IoError naming it (exit code 5), nothing written.
  EXPECT_THROW(WriteOutput(path + "/x", "y"), IoError);
  EXPECT_EQ(ReadAll(path), "second\n");
}

TEST(OutputFile, PathsAreCheckedBeforeAnyWork) {
  const std::string dir = TempDir("plateball_output_paths");
  const std::string in = dir + "/in.json";
  WriteOutput(in, "{}\n");
  std::string message;
  EXPECT_EQ(CodeFor(
                [&] {
                  CheckOutputPaths({{"--out", dir + "/a"}, {"--svg", dir + "/./a"}});
                },
                &message),
            kExitBadInput);
  EXPECT_NE(message.find("--out and --svg"), std::string::npos) << message;
  EXPECT_EQ(CodeFor([&] { CheckOutputPaths({{"--out", in}}, {{"PROBLEM.json", in}}); }, &message), kExitBadInput);
  EXPECT_NE(message.find("--out and PROBLEM.json"), std::string::npos) << message;
  EXPECT_EQ(CodeFor([&] { CheckOutputPaths({{"--out", "-"}, {"--svg", "-"}}); }, &message), kExitBadInput);
  EXPECT_EQ(CodeFor([&] { CheckOutputPaths({{"--out", dir + "/missing/a.json"}}); }, &message), kExitIoError);
  EXPECT_NE(message.find("missing/a.json"), std::string::npos) << message;
  EXPECT_NO_THROW(CheckOutputPaths({{"--out", "-"}, {"--svg", dir + "/b.svg"}, {"--csv", ""}}, {{"PROBLEM.json", in}}));
  EXPECT_NO_THROW(CheckOutputPaths({{"--out", "/dev/null"}}));
}

TEST(CommandLine, SeedsAreUnsigned64BitIntegers) {
  EXPECT_EQ(ParseSeedOption("--seed", "0"), 0u);
  EXPECT_EQ(ParseSeedOption("--seed", "18446744073709551615"), 18446744073709551615ull);
  for (const char* bad : {"", "-1", "18446744073709551616", "1e3", "abc", " 1", "99999999999999999999999"}) {
    try {
      ParseSeedOption("--seed", bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()),
                std::string("command line: --seed: value \"") + bad + "\": must be an integer in [0, 2^64 - 1]");
    }
  }
}

TEST(CommandLine, BlankAndNonNumericValuesAreBadInputInEveryTool) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"tool", "--mu", ""}, {"tool", "--mu", "  "}, {"tool", "--mu", "abc"}}) {
    CLI::App app;
    double mu = 1;
    app.add_option("--mu", mu);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    EXPECT_EQ(ParseCommandLine(app, static_cast<int>(argv.size()), argv.data(), "tool"), kExitBadInput) << args[2];
  }
  CLI::App app;
  double mu = 1;
  app.add_option("--mu", mu);
  std::vector<std::string> args{"tool", "--mu", "2.5"};
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  EXPECT_FALSE(ParseCommandLine(app, 3, argv.data(), "tool").has_value());
  EXPECT_EQ(mu, 2.5);
}

TEST(PlanJson, OneLayoutWithOrWithoutSteps) {
  PlanSummary plan;
  plan.steps.resize(2);
  const Json full = PlanSummaryToJson(plan);
  const Json brief = PlanSummaryToJson(plan, false);
  std::vector<std::string> keys;
  for (auto it = brief.begin(); it != brief.end(); ++it) keys.push_back(it.key());
  // docs/output_contract.md: the four result fields first, "message" always present.
  const std::vector<std::string> expected{"status",
                                          "usable",
                                          "message",
                                          "report",
                                          "total_time",
                                          "max_pass_miss",
                                          "max_join_residual",
                                          "measured_error",
                                          "polyline_error",
                                          "bounds",
                                          "rotation_final",
                                          "final"};
  EXPECT_EQ(keys, expected);
  ASSERT_TRUE(full.contains("steps"));
  EXPECT_EQ(full["steps"].size(), 2u);
  EXPECT_FALSE(brief.contains("steps"));
  EXPECT_EQ(full["usable"].get<bool>(), plan.IsSolutionUsable());
}

TEST(OutputContract, EveryDocumentStartsWithTheHeader) {
  Problem p;
  p.source = "problems/some_problem.json";
  p.seed = 18446744073709551615ULL;
  const Json h = HeaderJson("plateball", "simulate", p, "problems/some_problem.json");
  std::vector<std::string> keys;
  for (auto it = h.begin(); it != h.end(); ++it) keys.push_back(it.key());
  EXPECT_EQ(keys,
            (std::vector<std::string>{
                "schema_version", "tool", "version", "command", "problem", "model", "integration", "seed"}));
  EXPECT_EQ(h["schema_version"].get<int>(), kSchemaVersion);
  EXPECT_EQ(h["problem"]["name"].get<std::string>(), "some_problem");  // no name: the file's stem
  EXPECT_EQ(h["seed"].get<std::uint64_t>(), 18446744073709551615ULL);
  EXPECT_EQ(h["integration"]["max_steps"].get<long>(), p.integration.max_steps);
  p.name = "named";
  const Json without = HeaderJson("plateball", "roll", p, "", false);
  EXPECT_TRUE(without["problem"]["file"].is_null());
  EXPECT_EQ(without["problem"]["name"].get<std::string>(), "named");
  EXPECT_FALSE(without.contains("model"));
}

TEST(OutputContract, ResultsHaveStatusUsableMessageReport) {
  const Json r = ResultJson("success", true, "", "Plan: success");
  std::vector<std::string> keys;
  for (auto it = r.begin(); it != r.end(); ++it) keys.push_back(it.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"status", "usable", "message", "report"}));
  Json doc{{"a", 1}};
  Append(doc, Json{{"b", 2}, {"c", 3}});
  EXPECT_EQ(DumpJson(doc), "{\n  \"a\": 1,\n  \"b\": 2,\n  \"c\": 3\n}\n");
}
