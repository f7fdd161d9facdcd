// The status words of docs/output_contract.md ("Status words") against the library: every value
// of every `enum class ...Status` in include/plateball/*.h has its ToString word in the table, and
// every row of the table is a word of its enum. The enumerators are counted in the headers, so a
// value added to an enum (or a new status enum) without its row fails here.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>

#include "plateball/angle_form.h"
#include "plateball/controller.h"
#include "plateball/convergence.h"
#include "plateball/exact_arrival.h"
#include "plateball/execution.h"
#include "plateball/fewest_impulses.h"
#include "plateball/identify.h"
#include "plateball/impulse_planner.h"
#include "plateball/isoparallel.h"
#include "plateball/isoparallel_certificate.h"
#include "plateball/join.h"
#include "plateball/monte_carlo.h"
#include "plateball/reach.h"
#include "plateball/rig_planner.h"

using namespace plateball;

namespace {

const std::filesystem::path kSource = PLATEBALL_SOURCE_DIR;

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// enum name -> its enumerators (k...), from `enum class NAME {` ... `};` of each header.
std::map<std::string, int> EnumeratorCounts(const std::filesystem::path& folder) {
  std::map<std::string, int> counts;
  const std::regex head(R"(enum class (\w+Status) \{([^}]*)\};)");
  const std::regex value(R"((^|\n)\s*k[A-Z]\w*\s*(=[^,\n]*)?,)");
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".h") continue;
    const std::string text = ReadText(entry.path());
    for (std::sregex_iterator it(text.begin(), text.end(), head), end; it != end; ++it) {
      const std::string body = (*it)[2].str();
      counts[(*it)[1].str()] = static_cast<int>(
          std::distance(std::sregex_iterator(body.begin(), body.end(), value), std::sregex_iterator()));
    }
  }
  return counts;
}

// (enum, word) of every row "| `ENUM` ... | `word` | meaning |" of the "Status words" section.
std::set<std::pair<std::string, std::string>> TableRows() {
  const std::string doc = ReadText(kSource / "docs" / "output_contract.md");
  const std::size_t begin = doc.find("## 6. Status words");
  EXPECT_NE(begin, std::string::npos) << "docs/output_contract.md has no section \"6. Status words\"";
  std::set<std::pair<std::string, std::string>> rows;
  if (begin == std::string::npos) return rows;
  const std::size_t end = doc.find("\n## ", begin + 1);
  const std::string section = doc.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
  const std::regex row(R"(\n\| `(\w+)`[^|]*\| `(\w+)` \|)");
  for (std::sregex_iterator it(section.begin(), section.end(), row), stop; it != stop; ++it)
    rows.insert({(*it)[1].str(), (*it)[2].str()});
  return rows;
}

// The words of the first `count` values of E.
template <class E>
std::function<std::set<std::string>(int)> Words() {
  return [](int count) {
    std::set<std::string> words;
    for (int i = 0; i < count; ++i) words.insert(ToString(static_cast<E>(i)));
    return words;
  };
}

// Every status enum of include/plateball/*.h (the OMPL steering's, in ompl/, is counted separately).
const std::map<std::string, std::function<std::set<std::string>(int)>>& Enums() {
  static const std::map<std::string, std::function<std::set<std::string>(int)>> enums{
      {"AngleFormStatus", Words<AngleFormStatus>()},
      {"ControllerStatus", Words<ControllerStatus>()},
      {"ConvergenceStatus", Words<ConvergenceStatus>()},
      {"ExactArrivalStatus", Words<ExactArrivalStatus>()},
      {"ExecutionStatus", Words<ExecutionStatus>()},
      {"FewestImpulsesStatus", Words<FewestImpulsesStatus>()},
      {"IdentifyStatus", Words<IdentifyStatus>()},
      {"IsoparallelCertificateStatus", Words<IsoparallelCertificateStatus>()},
      {"IsoparallelStatus", Words<IsoparallelStatus>()},
      {"JoinStatus", Words<JoinStatus>()},
      {"MonteCarloStatus", Words<MonteCarloStatus>()},
      {"PlanStatus", Words<PlanStatus>()},
      {"ReachStatus", Words<ReachStatus>()},
      {"RigPlanStatus", Words<RigPlanStatus>()},
  };
  return enums;
}

TEST(StatusWords, EveryStatusEnumOfThePublicHeadersIsChecked) {
  const std::map<std::string, int> counts = EnumeratorCounts(kSource / "include" / "plateball");
  ASSERT_FALSE(counts.empty());
  for (const auto& [name, count] : counts) {
    EXPECT_EQ(Enums().count(name), 1u) << name << ": a status enum this test does not call ToString of";
    EXPECT_GE(count, 2) << name << ": enumerators not found in its header";
  }
  EXPECT_EQ(counts.size(), Enums().size());
}

TEST(StatusWords, EveryWordIsInTheTableAndEveryRowIsAWord) {
  const std::map<std::string, int> counts = EnumeratorCounts(kSource / "include" / "plateball");
  const auto rows = TableRows();
  for (const auto& [name, words_of] : Enums()) {
    ASSERT_EQ(counts.count(name), 1u) << name;
    const std::set<std::string> words = words_of(counts.at(name));
    EXPECT_EQ(words.size(), static_cast<std::size_t>(counts.at(name))) << name << ": two values with one word";
    for (const std::string& word : words) {
      EXPECT_NE(word, "unknown") << name << ": a value without its word";
      EXPECT_EQ(rows.count({name, word}), 1u) << name << " " << word << ": missing from docs/output_contract.md";
    }
    for (const auto& [enum_name, word] : rows) {
      if (enum_name == name) {
        EXPECT_EQ(words.count(word), 1u) << name << " " << word << ": not a word of the enum";
      }
    }
  }
}

TEST(StatusWords, TheOmplConnectionStatusHasOneRowPerValue) {
  const std::map<std::string, int> counts = EnumeratorCounts(kSource / "include" / "plateball" / "ompl");
  ASSERT_EQ(counts.count("ConnectionStatus"), 1u);
  int rows = 0;
  for (const auto& row : TableRows()) rows += row.first == "ConnectionStatus" ? 1 : 0;
  EXPECT_EQ(rows, counts.at("ConnectionStatus"));
}

}  // namespace
