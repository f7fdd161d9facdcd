// Replays every input in fuzz/regressions/<target>/ (crashes found by fuzzing, kept forever) and
// the seed corpora through the fuzz entry points of fuzz/fuzz_entries.h. The entries abort on a
// defect, so a passing test means no input regressed.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "../fuzz/fuzz_entries.h"
#include "support/test_support.h"

namespace fs = std::filesystem;

namespace {
std::vector<std::vector<std::uint8_t>> Inputs(const std::vector<std::string>& dirs) {
  std::vector<std::vector<std::uint8_t>> out;
  for (const std::string& d : dirs) {
    const fs::path dir = plateball::testing::SourcePath(d);
    if (!fs::exists(dir)) continue;
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && e.path().filename() != ".keep") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
      std::ifstream in(f, std::ios::binary);
      out.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
  }
  return out;
}
}  // namespace

TEST(FuzzRegression, ProblemReaderInputsNeverCrash) {
  const auto inputs =
      Inputs({"fuzz/regressions/problem_reader_fuzzer", "fuzz/seeds/problem_reader_fuzzer", "problems"});
  ASSERT_GE(inputs.size(), 3u);  // the seeds and the problems folder are always there
  for (const auto& in : inputs) plateball::fuzz::ProblemReader(in.data(), in.size());
}

TEST(FuzzRegression, SolveEntriesInputsNeverCrash) {
  const auto inputs = Inputs({"fuzz/regressions/solve_entries_fuzzer", "fuzz/seeds/solve_entries_fuzzer"});
  ASSERT_GE(inputs.size(), 3u);
  for (const auto& in : inputs) plateball::fuzz::SolveEntries(in.data(), in.size());
}

TEST(FuzzRegression, ReachInputsNeverCrash) {
  const auto inputs = Inputs({"fuzz/regressions/reach_fuzzer", "fuzz/seeds/reach_fuzzer"});
  ASSERT_GE(inputs.size(), 3u);
  for (const auto& in : inputs) plateball::fuzz::ReachEntry(in.data(), in.size());
}

TEST(FuzzRegression, IsoparallelInputsNeverCrash) {
  const auto inputs = Inputs({"fuzz/regressions/isoparallel_fuzzer", "fuzz/seeds/isoparallel_fuzzer"});
  ASSERT_GE(inputs.size(), 3u);
  for (const auto& in : inputs) plateball::fuzz::IsoparallelEntry(in.data(), in.size());
}

TEST(FuzzRegression, SteerInputsNeverCrash) {
  const auto inputs = Inputs({"fuzz/regressions/steer_fuzzer", "fuzz/seeds/steer_fuzzer", "problems"});
  ASSERT_GE(inputs.size(), 3u);
  for (const auto& in : inputs) plateball::fuzz::SteerEntry(in.data(), in.size());
}

TEST(FuzzRegression, ViewInputsNeverCrash) {
  const auto inputs = Inputs({"fuzz/regressions/view_input_fuzzer", "fuzz/seeds/view_input_fuzzer"});
  ASSERT_GE(inputs.size(), 3u);
  for (const auto& in : inputs) plateball::fuzz::ViewEntry(in.data(), in.size());
}
