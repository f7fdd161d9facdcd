#include "problem_io/value_text.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>

namespace plateball::internal::problem_io {
namespace {

std::string Truncate(std::string s, std::size_t n) {
  if (s.size() > n) s = s.substr(0, n) + "...";
  return s;
}

// Compact, bounded rendering of a JSON value (bounded depth and length: never recursive without
// limit, whatever the input).
void AppendValueText(const json& j, int depth, std::string* out) {
  if (out->size() > 160) {
    *out += "...";
    return;
  }
  switch (j.type()) {
    case json::value_t::null:
      *out += "null";
      return;
    case json::value_t::boolean:
      *out += j.get<bool>() ? "true" : "false";
      return;
    case json::value_t::number_integer:
      *out += std::to_string(j.get<std::int64_t>());
      return;
    case json::value_t::number_unsigned:
      *out += std::to_string(j.get<std::uint64_t>());
      return;
    case json::value_t::number_float:
      *out += NumberText(j.get<double>());
      return;
    case json::value_t::string:
      *out += Truncate(json(j.get<std::string>()).dump(-1, ' ', false, json::error_handler_t::replace), 64);
      return;
    case json::value_t::array: {
      if (depth >= 3 || j.size() > 12) {
        *out += "[array of " + std::to_string(j.size()) + "]";
        return;
      }
      *out += "[";
      bool first = true;
      for (const json& e : j) {
        if (!first) *out += ", ";
        first = false;
        AppendValueText(e, depth + 1, out);
      }
      *out += "]";
      return;
    }
    case json::value_t::object: {
      if (j.empty()) {
        *out += "{}";
        return;
      }
      *out += "{object with keys ";
      bool first = true;
      int shown = 0;
      for (auto it = j.begin(); it != j.end(); ++it) {
        if (++shown > 8) {
          *out += ", ...";
          break;
        }
        if (!first) *out += ", ";
        first = false;
        *out += Truncate(it.key(), 32);
      }
      *out += "}";
      return;
    }
    default:
      *out += "(binary)";
      return;
  }
}

}  // namespace

std::string NumberText(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::floor(v) == v && std::abs(v) < 1e15) {  // integral: no exponent, no ".0"
    std::ostringstream os;
    os << static_cast<long long>(v);
    return (v == 0 && std::signbit(v)) ? "-0" : os.str();
  }
  // Shortest representation that reads back to the same double.
  for (int precision = 1; precision <= 17; ++precision) {
    std::ostringstream os;
    os.precision(precision);
    os << v;
    if (std::strtod(os.str().c_str(), nullptr) == v) return os.str();
  }
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

std::string ValueText(const json& j) {
  std::string s;
  AppendValueText(j, 0, &s);
  return s;
}

std::string VectorText(const double* v, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += (i ? ", " : "") + NumberText(v[i]);
  return s + "]";
}

}  // namespace plateball::internal::problem_io
