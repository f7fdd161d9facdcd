// `plateball view RESULT.json --html OUT.html`: a self-contained 3-D page of a result of
// `plateball simulate`, `plan`, `steer` or an isoparallel solution: the data (re-simulated by the
// library, view_data.h), the page's script and three.js are all in the one HTML file, which opens
// offline and makes no network request.
#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "common/command_registry.h"
#include "common/errors.h"
#include "common/exit_codes.h"
#include "common/input_file.h"
#include "common/invalid_input.h"
#include "common/limits.h"
#include "common/number_format.h"
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

// Fills every marker of the template in one pass over the template: each marker is found in the
// template itself, never in text already filled in, so data that contains a marker stays data.
std::string FillTemplate(const std::string& page, const std::vector<std::pair<std::string, std::string>>& fills) {
  std::vector<std::pair<std::size_t, std::size_t>> at;  // (position in page, index in fills)
  for (std::size_t k = 0; k < fills.size(); ++k) {
    const std::size_t pos = page.find(fills[k].first);
    if (pos == std::string::npos) throw std::logic_error("web/view.html lacks the marker " + fills[k].first);
    at.emplace_back(pos, k);
  }
  std::sort(at.begin(), at.end());
  std::string out;
  std::size_t from = 0;
  for (const auto& [pos, k] : at) {
    out.append(page, from, pos - from);
    out += fills[k].second;
    from = pos + fills[k].first.size();
  }
  out.append(page, from, std::string::npos);
  return out;
}

// JSON text for a <script> element: '<', '>' and '&' (which could open "<!--", "<script" or "</script")
// and U+2028/U+2029 (line terminators in older JavaScript) are written as \uXXXX escapes. They can only
// occur inside JSON strings, where the escape denotes the same character, so the value is unchanged.
std::string ScriptSafeJson(const nlohmann::json& value) {
  const std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '<')
      out += "\\u003c";
    else if (c == '>')
      out += "\\u003e";
    else if (c == '&')
      out += "\\u0026";
    else if (c == '\xE2' && i + 2 < text.size() && text[i + 1] == '\x80' &&
             (text[i + 2] == '\xA8' || text[i + 2] == '\xA9')) {
      out += text[i + 2] == '\xA8' ? "\\u2028" : "\\u2029";
      i += 2;
    } else
      out += c;
  }
  return out;
}

std::string HtmlEscape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

int RunView(const ViewCliOptions& o) {
  CheckOutputPaths({{"--html", o.html}}, {{"RESULT.json", o.result}, {"--problem", o.problem}});
  const long long samples = RequireIntegerInRange("--samples", o.samples, 100, 100'000);
  const nlohmann::json doc = view::ParseResult(o.result, ReadInputText(o.result));
  const view::ResultFields fields(nlohmann::json::parse(view::kResultFields));
  const view::ResultReader reader(o.result, doc, fields);
  view::ViewOptions options;
  options.problem_file = o.problem;
  options.samples = static_cast<int>(samples);
  const view::ViewData data = view::BuildView(reader, options);
  view::CheckDrawable(o.result, data);
  nlohmann::json page_data = view::ViewDataToJson(data);
  page_data["generator"] = std::string("plateball ") + PLATEBALL_VERSION_STRING + ", three.js " + view::kThreeVersion;
  const std::string page = FillTemplate(view::kViewTemplate,
                                        {{"@TITLE@", HtmlEscape(data.title)},
                                         {"/*@THREE@*/", view::kThreeScript},
                                         {"/*@VIEW@*/", view::kViewScript},
                                         {"\"@DATA@\"", ScriptSafeJson(page_data)}});
  WriteOutput(o.html, page);
  return kExitSuccess;
}

std::function<int()> SetupView(CLI::App& sub) {
  auto o = std::make_shared<ViewCliOptions>();
  sub.add_option("RESULT.json",
                 o->result,
                 "a result of plateball simulate, plan, steer, isoparallel or of isoparallel_solve --out (\"-\": "
                 "standard input)")
      ->required();
  sub.add_option("--html", o->html, "write the page to this file (\"-\": standard output)")->required();
  sub.add_option(
      "--problem", o->problem, "the problem file of a plan or steer result (default: the result's problem.file)");
  sub.add_option("--samples", o->samples, "samples of the motion at least, 100 ... 100000 (default 4000)");
  sub.footer(
      "Writes one self-contained HTML page (data, script and three.js inside; opens offline, no network):\n"
      "the plates, the ball with markings (orientation A(t) from the library, slerp between dense samples),\n"
      "the upper plate moving at twice the ball's speed, the traced contact path, the planned path dashed,\n"
      "the impulses with the plate velocity change as arrows, a ghost ball rolling along the planned path,\n"
      "a time slider, play/pause, speed, and the orientation error against time. For a steer result with a\n"
      "rig: the plate region, the obstacles with their clearance, the upper plate's stroke box and the replay\n"
      "check's verdict and margins.\n"
      "Example: plateball plan problems/circle.json --out circle.json && plateball view circle.json --html "
      "circle.html\n"
      "Exit codes: 0 ok, 2 usage, 3 invalid result (the field is named), 5 unreadable or unwritable file.");
  return [o] { return RunView(*o); };
}

const CommandRegistrar kRegistrar{
    {"view", "write a self-contained interactive 3-D page of a result (HTML)", SetupView}};

}  // namespace
}  // namespace plateball::tools
