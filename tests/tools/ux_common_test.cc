// Unit tests of the tool helpers: streamed sample documents (sample_table.h) against the
// whole-document writer, CSV columns, the progress text's ETA, the figure size option, the SI
// scales (units.h) and the figure's axes and legend (svg.h).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/json_output.h"
#include "common/progress.h"
#include "common/sample_table.h"
#include "common/svg.h"
#include "common/units.h"
#include "plateball/problem_io.h"

namespace plateball::tools {
namespace {

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Json SampleAt(std::size_t i) {
  return Json{{"t", 0.5 * static_cast<double>(i)}, {"x", Json::array({1.0 / 3.0, -2.0})}, {"energy", 1.0}};
}

// The streamed document equals, byte for byte, the document built whole and dumped by DumpJson.
TEST(SampleTable, StreamedDocumentEqualsTheWholeDocument) {
  for (std::size_t count : {std::size_t{1}, std::size_t{2}, std::size_t{5}}) {
    Json header{{"command", "simulate"}, {"t_end", 2.0}};
    Json whole = header;
    whole["samples"] = Json::array();
    for (std::size_t i = 0; i < count; ++i) whole["samples"].push_back(SampleAt(i));
    const std::string path = ::testing::TempDir() + "/ux_samples.json";
    WriteSampleDocument(path, header, count, SampleAt, nullptr);
    EXPECT_EQ(ReadAll(path), DumpJson(whole)) << count;
    std::remove(path.c_str());
  }
}

TEST(SampleTable, CsvHasOneColumnPerNumberNamedByItsPath) {
  const std::string path = ::testing::TempDir() + "/ux_samples.csv";
  WriteSampleCsv(path, 2, SampleAt, nullptr);
  EXPECT_EQ(ReadAll(path), "t,x.0,x.1,energy\n0,0.3333333333333333,-2,1\n0.5,0.3333333333333333,-2,1\n");
  std::remove(path.c_str());
  EXPECT_THROW(CsvColumns(Json{{"t", std::nan("")}}), std::logic_error);
}

// A failing producer leaves no file behind (and the previous one untouched).
TEST(SampleTable, AFailedStreamLeavesThePreviousFile) {
  const std::string path = ::testing::TempDir() + "/ux_keep.csv";
  std::ofstream(path) << "previous\n";
  const SampleSource failing = [](std::size_t i) -> Json {
    if (i == 3) throw std::runtime_error("sample 3 failed");
    return SampleAt(i);
  };
  EXPECT_THROW(WriteSampleCsv(path, 10, failing, nullptr), std::runtime_error);
  EXPECT_EQ(ReadAll(path), "previous\n");
  std::remove(path.c_str());
}

TEST(Progress, TextShowsFractionElapsedAndEta) {
  // Half done after 2 s: the other half takes 2 s more.
  EXPECT_EQ(ProgressText(5, 10, 2), "50% (5 of 10), 2 s elapsed, ETA 2 s");
  EXPECT_EQ(ProgressText(1, 4, 30), "25% (1 of 4), 30 s elapsed, ETA 90 s");
  EXPECT_EQ(ProgressText(0, 0, 3), "3 s elapsed");
}

TEST(Progress, QuietPrintsNothingAndAlwaysPrintsTheFinalLine) {
  testing::internal::CaptureStderr();
  {
    Progress p("quiet", 10, ProgressMode::kQuiet, false);
    p.Update(10);
  }
  {
    Progress p("auto-on-a-pipe", 10, ProgressMode::kAuto, false);
    p.Update(10);
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  testing::internal::CaptureStderr();
  {
    Progress p("always", 10, ProgressMode::kAlways, false);
    p.Update(10);
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr().rfind("always: done (10 of 10) in ", 0), 0u);
}

TEST(FigureSize, ParsesWidthByHeightAndRejectsOutOfRange) {
  const FigureSize s = ParseFigureSize("--figure-size", "800x600");
  EXPECT_EQ(s.width, 800);
  EXPECT_EQ(s.height, 600);
  for (const char* bad : {"800", "x600", "10x10", "800x9000", "-800x600", "8e2x600", ""})
    EXPECT_THROW(ParseFigureSize("--figure-size", bad), std::invalid_argument) << bad;
}

TEST(Units, ScalesAreTheRadiusForLengthsAndVelocitiesAndOneForTime) {
  Problem p = ReadProblemFile(std::string(PLATEBALL_SOURCE_DIR) + "/problems/physical_units.json");
  ASSERT_TRUE(ScalesOf(p).has_value());
  EXPECT_EQ(ScalesOf(p)->length_m, 0.02);
  EXPECT_EQ(ScalesOf(p)->time_s, 1.0);
  Json doc{{"period", 3.0}, {"steps", Json::array({Json{{"plate_velocity_change", Json::array({1.0, -2.0, 0.0})}}})}};
  AddPhysicalUnits(p, &doc);
  EXPECT_EQ(doc["si"]["period"], 3.0);
  EXPECT_EQ(doc["steps"][0]["si"]["plate_velocity_change"], Json::array({0.02, -0.04, 0.0}));
  // E = mu (I1 + M r^2) / 2 with M = ball + 4 plate (the plate moves at twice the centre's speed).
  EXPECT_NEAR(doc["units"]["kinetic_energy_J"].get<double>(), 0.5 * 4.0 * (1.6e-5 + 0.3 * 0.02 * 0.02), 1e-18);
  Problem plain;  // no physical section: nothing added
  Json untouched{{"period", 3.0}};
  AddPhysicalUnits(plain, &untouched);
  EXPECT_EQ(untouched, (Json{{"period", 3.0}}));
}

TEST(SvgFigure, AxesLegendAndStartGoalAreDrawn) {
  SvgFigure fig(640, 480);
  fig.Polyline({{0, 0}, {3, 3}}, {"red", 1.5, "6,4", "none"});
  fig.Start({0, 0}, {1, 1}, "x0");
  fig.Goal({3, 3}, {1, 1}, "x1");
  fig.Legend("path", {"red", 1.5, "6,4", "none"});
  fig.Legend("points", {"black", 1.0, "", "black"});
  const std::string svg = fig.Render();
  EXPECT_NE(svg.find("x (ball radii)"), std::string::npos);
  EXPECT_NE(svg.find("start (arrow: direction of motion)"), std::string::npos);
  EXPECT_NE(svg.find("width=\"640\" height=\"480\""), std::string::npos);
  // The dashed legend swatch is dashed like its curve; the point swatch is a circle.
  const std::size_t first_dash = svg.find("stroke-dasharray=\"6,4\"");
  ASSERT_NE(first_dash, std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray=\"6,4\"", first_dash + 1), std::string::npos);  // curve and swatch
  const std::size_t points_label = svg.find(">points</text>");
  ASSERT_NE(points_label, std::string::npos);
  EXPECT_NE(svg.rfind("<circle", points_label), std::string::npos);
  EXPECT_EQ(CurveDirection({{0, 0}, {0, 0}, {2, 0}}, false), Eigen::Vector2d(2, 0));
  EXPECT_EQ(CurveDirection({{0, 0}, {1, 1}, {1, 1}}, true), Eigen::Vector2d(1, 1));
}

}  // namespace
}  // namespace plateball::tools
