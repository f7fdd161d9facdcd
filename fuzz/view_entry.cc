// The view entry of fuzz_entries.h: `plateball view`'s reader and re-simulation on any bytes.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_entries.h"
#include "view/view_assets.h"
#include "view/view_data.h"

namespace plateball::fuzz {
namespace {

[[noreturn]] void ViewDefect(const std::string& what) {
  std::fprintf(stderr, "fuzz defect: %s\n", what.c_str());
  std::abort();
}

template <typename T>
void RequireFinitePoints(const char* what, const std::vector<T>& points) {
  for (const T& p : points)
    if (!p.allFinite()) ViewDefect(std::string("view: ") + what + " is not finite in page data");
}

// The problem file of a plan or steer result: only by its file name, in the source tree's problems/
// folder (a fuzzed path must not open arbitrary files); a name not there gives a read error.
std::string ProblemFileFor(const nlohmann::json& doc) {
  const std::filesystem::path problems = std::filesystem::path(PLATEBALL_SOURCE_DIR) / "problems";
  if (doc.is_object()) {
    const auto header = doc.find("problem");
    if (header != doc.end() && header->is_object()) {
      const auto file = header->find("file");
      if (file != header->end() && file->is_string()) {
        const std::filesystem::path name = std::filesystem::path(file->get<std::string>()).filename();
        if (!name.empty() && name != "." && name != "..") return (problems / name).string();
      }
    }
  }
  return (problems / "(none).json").string();
}

}  // namespace

void ViewEntry(const std::uint8_t* data, std::size_t size) {
  static const tools::view::ResultFields fields(nlohmann::json::parse(tools::view::kResultFields));
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const nlohmann::json doc = tools::view::ParseResult("fuzz.json", text);
    const tools::view::ResultReader reader("fuzz.json", doc, fields);
    tools::view::ViewOptions options;
    options.samples = 100;  // the tool's smallest --samples
    options.problem_file = ProblemFileFor(doc);
    const tools::view::ViewData view = tools::view::BuildView(reader, options);
    tools::view::CheckDrawable("fuzz.json", view);
    for (const double t : view.t)
      if (!std::isfinite(t)) ViewDefect("view: a sample time is not finite in page data");
    RequireFinitePoints("x", view.x);
    RequireFinitePoints("A", view.A);
    RequireFinitePoints("ghost_x", view.ghost_x);
    RequireFinitePoints("ghost_A", view.ghost_A);
    RequireFinitePoints("planned", view.planned);
    for (const tools::view::ViewImpulse& k : view.impulses)
      if (!std::isfinite(k.t) || !k.x.allFinite() || !k.plate_velocity_change.allFinite())
        ViewDefect("view: an impulse is not finite in page data");
    if (!std::isfinite(view.resimulation_mismatch)) ViewDefect("view: resimulation_mismatch is not finite");
    (void)tools::view::ViewDataToJson(view).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  } catch (const std::invalid_argument& e) {
    // Bad input names the result file and its field ("fuzz.json: steps[0].duration: value ..."),
    // or the problem file it reads; never a variable of the code ("t: value ...").
    const std::string message = e.what();
    if (message.rfind("fuzz.json: ", 0) != 0 && message.find("/problems/") == std::string::npos)
      ViewDefect("view: a message that names no field of the result: " + message);
  } catch (const std::runtime_error&) {  // a reported failure (an integration over its step bound)
  }
}

}  // namespace plateball::fuzz
