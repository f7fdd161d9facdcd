#include "problem_io/json_parse.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "plateball/limits.h"

namespace plateball::internal::problem_io {
namespace {

// ------------------------------------------------------------------ parsing with diagnostics
// Builds the document through nlohmann's SAX interface in one pass (linear in the input: the
// callback parser rescans the parent container after each object, quadratic for a file of many
// small objects), rejects a key given twice in one object (JSON allows it, but it silently drops
// data), caps the nesting depth, and names the path of the value being parsed.
class DomBuilder {
 public:
  explicit DomBuilder(json* root) : root_(root) {}

  bool null() { return Add(json(nullptr)) != nullptr; }
  bool boolean(bool v) { return Add(json(v)) != nullptr; }
  bool number_integer(json::number_integer_t v) { return Add(json(v)) != nullptr; }
  bool number_unsigned(json::number_unsigned_t v) { return Add(json(v)) != nullptr; }
  bool number_float(json::number_float_t v, const json::string_t& /*text*/) { return Add(json(v)) != nullptr; }
  bool string(json::string_t& v) { return Add(json(std::move(v))) != nullptr; }
  bool binary(json::binary_t& v) { return Add(json::binary(std::move(v))) != nullptr; }
  bool start_object(std::size_t /*size*/) { return Open(json::object()); }
  bool start_array(std::size_t /*size*/) { return Open(json::array()); }
  bool key(json::string_t& k) {
    Frame& f = frames_.back();
    f.key = std::move(k);
    if (f.value->contains(f.key) && duplicate_path_.empty()) duplicate_path_ = CurrentPath();
    return true;
  }
  bool end_object() { return Close(); }
  bool end_array() { return Close(); }
  template <class Exception>
  bool parse_error(std::size_t /*position*/, const std::string& /*last_token*/, const Exception& e) {
    throw e;  // handled by ParseJson, as with json::parse
  }

  bool depth_exceeded() const { return depth_exceeded_; }
  const std::string& duplicate_path() const { return duplicate_path_; }
  /// Path of the value being parsed (empty at the top level).
  std::string CurrentPath() const {
    std::string s;
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      if (f.value->is_array()) {
        const std::size_t n = f.value->size();
        s += "[" + std::to_string(i + 1 < frames_.size() && n > 0 ? n - 1 : n) + "]";
      } else {
        s += (s.empty() ? "" : ".") + f.key;
      }
    }
    return s;
  }

 private:
  struct Frame {
    json* value;
    std::string key;
  };
  // Stores v in the open container (or as the root); returns where it went.
  json* Add(json v) {
    if (frames_.empty()) {
      *root_ = std::move(v);
      return root_;
    }
    Frame& f = frames_.back();
    if (f.value->is_array()) {
      f.value->push_back(std::move(v));
      return &f.value->back();
    }
    json& slot = (*f.value)[f.key];
    slot = std::move(v);
    return &slot;
  }
  bool Open(json container) {
    if (frames_.size() >= static_cast<std::size_t>(limits::kMaxJsonDepth)) {
      depth_exceeded_ = true;
      return false;  // stops the parser
    }
    json* slot = Add(std::move(container));
    frames_.push_back({slot, {}});
    return true;
  }
  bool Close() {
    frames_.pop_back();
    return true;
  }

  json* root_;
  std::vector<Frame> frames_;
  std::string duplicate_path_;
  bool depth_exceeded_ = false;
};

}  // namespace

namespace {
// A path inside the document under its root's name ("" is the root itself).
std::string UnderRoot(const std::string& root, const std::string& path) {
  if (path.empty()) return root;
  if (root == "(document)") return path;
  return root + (path[0] == '[' ? "" : ".") + path;
}
}  // namespace

json ParseJson(const std::string& text, const FieldReader& reader, const std::string& root_field) {
  // nlohmann's lexer reads a NUL byte as the end of the input: anything after it would be
  // ignored silently.
  const std::size_t nul = text.find('\0');
  if (nul != std::string::npos)
    reader.Fail(root_field,
                "(NUL byte at offset " + std::to_string(nul) + ")",
                "a problem file is JSON text; it must not contain a NUL byte");
  json root;
  DomBuilder detector(&root);
  try {
    json::sax_parse(text, &detector, json::input_format_t::json, /*strict=*/true, /*ignore_comments=*/false);
  } catch (const json::parse_error& e) {
    // e.byte is the 1-based offset of the last character read (the offending token's end);
    // line and column are counted here (nlohmann's column is off after a newline).
    std::string what = e.what();
    const std::string marker = "column ";
    const auto at = what.find(marker);
    if (at != std::string::npos) {
      const auto colon = what.find(": ", at);
      if (colon != std::string::npos) what = what.substr(colon + 2);
    }
    const std::size_t end = std::min<std::size_t>(e.byte, text.size());
    const std::size_t last = end > 0 ? end - 1 : 0;
    std::size_t line = 1, line_start = 0;
    for (std::size_t i = 0; i < last && i < text.size(); ++i)
      if (text[i] == '\n') {
        ++line;
        line_start = i + 1;
      }
    what = "line " + std::to_string(line) + ", column " + std::to_string(last - line_start + 1) + ": " + what;
    const std::size_t begin = end > 24 ? end - 24 : 0;
    std::string excerpt = text.substr(begin, end - begin);
    for (char& c : excerpt)
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = ' ';
    reader.Fail(root_field, "'" + excerpt + "'", "malformed JSON at " + what);
  } catch (const json::exception& e) {
    // e.g. out_of_range.406, a number that overflows a double: name the field being parsed and
    // the offending token.
    std::string what = e.what();
    const auto close = what.find("] ");
    if (close != std::string::npos) what = what.substr(close + 2);
    std::string value = "(see message)";
    const auto q0 = what.find('\'');
    const auto q1 = q0 == std::string::npos ? q0 : what.find('\'', q0 + 1);
    if (q1 != std::string::npos) value = what.substr(q0 + 1, q1 - q0 - 1);
    const std::string field = detector.CurrentPath();
    reader.Fail(UnderRoot(root_field, field), value, "malformed JSON: " + what);
  }
  if (detector.depth_exceeded())
    reader.Fail(
        UnderRoot(root_field, detector.CurrentPath()),
        "(nested arrays/objects)",
        "nested deeper than " + std::to_string(limits::kMaxJsonDepth) + " levels (the limit of a problem file)");
  if (!detector.duplicate_path().empty())
    reader.Fail(
        UnderRoot(root_field, detector.duplicate_path()), "(duplicate)", "key given more than once in the same object");
  return root;
}

}  // namespace plateball::internal::problem_io
