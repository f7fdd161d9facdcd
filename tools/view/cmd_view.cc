// `plateball view RESULT.json --html OUT.html` (issue 14): a self-contained 3-D page of a result of
// `plateball simulate`, `plan`, `steer` or an isoparallel solution: the data (re-simulated by the
// library, view_data.h), the page's script and three.js are all in the one HTML file, which opens
// offline and makes no network request.
#include <memory>
#include <stdexcept>
#include <string>

#include "common/command_registry.h"
#include "common/errors.h"
#include "common/exit_codes.h"
#include "common/input_file.h"
#include "common/limits.h"
#include "common/output_file.h"
#include "common/problem_options.h"
#include "plateball/version.h"
#include "view/view_assets.h"
#include "view/view_data.h"

namespace plateball::tools {
namespace {

struct ViewCliOptions {
  std::string result;
  std::string html;
  std::string problem;
  long long samples = 4000;
};

nlohmann::json ParseResult(const std::string& file, const std::string& text) {
  const nlohmann::json::parser_callback_t depth_limit = [&](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
    if (depth > kMaxJsonDepth)
      throw std::invalid_argument(file + ": (document): value (nested deeper than " + std::to_string(kMaxJsonDepth) +
                                  "): arrays and objects may be nested at most that deep");
    return true;
  };
  try {
    return nlohmann::json::parse(text, depth_limit);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(file + ": (document): value (see message): malformed JSON: " + e.what());
  }
}

// Replaces the one occurrence of `marker` in `page` by `text`.
void Fill(std::string* page, const std::string& marker, const std::string& text) {
  const std::size_t at = page->find(marker);
  if (at == std::string::npos) throw std::logic_error("web/view.html lacks the marker " + marker);
  page->replace(at, marker.size(), text);
}

// Text inside <script>: "</" could close the element, so it is written "<\/" (same JSON value).
std::string ScriptSafe(std::string text) {
  for (std::size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3)) text.insert(at + 1, "\\");
  return text;
}

std::string HtmlEscape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

int RunView(const ViewCliOptions& o) {
  CheckOutputPaths({{"--html", o.html}}, {{"RESULT.json", o.result}, {"--problem", o.problem}});
  const long long samples = RequireIntegerInRange("--samples", o.samples, 100, 100'000);
  const nlohmann::json doc = ParseResult(o.result, ReadInputText(o.result));
  const view::ResultFields fields(nlohmann::json::parse(view::kResultFields));
  const view::ResultReader reader(o.result, doc, fields);
  view::ViewOptions options;
  options.problem_file = o.problem;
  options.samples = static_cast<int>(samples);
  const view::ViewData data = view::BuildView(reader, options);
  nlohmann::json page_data = view::ViewDataToJson(data);
  page_data["generator"] = std::string("plateball ") + PLATEBALL_VERSION_STRING + ", three.js " + view::kThreeVersion;
  std::string page = view::kViewTemplate;
  Fill(&page, "@TITLE@", HtmlEscape(data.title));
  Fill(&page, "/*@THREE@*/", view::kThreeScript);
  Fill(&page, "/*@VIEW@*/", view::kViewScript);
  Fill(&page, "\"@DATA@\"", ScriptSafe(page_data.dump()));
  WriteOutput(o.html, page);
  return kExitSuccess;
}

std::function<int()> SetupView(CLI::App& sub) {
  auto o = std::make_shared<ViewCliOptions>();
  sub.add_option("RESULT.json", o->result, "a result of plateball simulate, plan, steer, isoparallel or of isoparallel_solve --out (\"-\": standard input)")
      ->required();
  sub.add_option("--html", o->html, "write the page to this file (\"-\": standard output)")->required();
  sub.add_option("--problem", o->problem,
                 "the problem file of a plan or steer result (default: the result's problem.file)");
  sub.add_option("--samples", o->samples, "samples of the motion at least, 100 ... 100000 (default 4000)");
  sub.footer(
      "Writes one self-contained HTML page (data, script and three.js inside; opens offline, no network):\n"
      "the plates, the ball with markings (orientation A(t) from the library, slerp between dense samples),\n"
      "the upper plate moving at twice the ball's speed, the traced contact path, the planned path dashed,\n"
      "the impulses with the plate velocity change as arrows, a ghost ball rolling along the planned path,\n"
      "a time slider, play/pause, speed, and the orientation error against time.\n"
      "Example: plateball plan problems/circle.json --out circle.json && plateball view circle.json --html circle.html\n"
      "Exit codes: 0 ok, 2 usage, 3 invalid result (the field is named), 5 unreadable or unwritable file.");
  return [o] { return RunView(*o); };
}

const CommandRegistrar kRegistrar{{"view", "write a self-contained interactive 3-D page of a result (HTML)", SetupView}};

}  // namespace
}  // namespace plateball::tools
