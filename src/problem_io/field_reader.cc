#include "problem_io/field_reader.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "check.h"

namespace plateball::internal::problem_io {

void FieldReader::Fail(const std::string& path, const std::string& value, const std::string& what) const {
  throw std::invalid_argument(internal::InvalidValueMessage(source_ + ": " + path, value, what));
}
void FieldReader::Fail(const std::string& path, const char* value, const std::string& what) const {
  Fail(path, std::string(value), what);
}
void FieldReader::Fail(const std::string& path, const json& value, const std::string& what) const {
  Fail(path, ValueText(value), what);
}

void FieldReader::Object(const json& j, const std::string& path, const std::vector<const char*>& allowed) const {
  if (!j.is_object()) Fail(path, j, "must be a JSON object");
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || it.key() == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      Fail(Join(path, it.key()), it.value(), "unknown key (allowed here: " + list + ")");
    }
  }
}

const json& FieldReader::Require(const json& obj, const std::string& path, const char* key) const {
  const json* v = Find(obj, key);
  if (!v) Fail(Join(path, key), std::string(kMissing), "required field is missing");
  return *v;
}

double FieldReader::Number(const json& v, const std::string& path) const {
  if (!v.is_number()) Fail(path, v, "must be a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) Fail(path, v, "must be a finite number");
  return d;
}
double FieldReader::Positive(const json& v, const std::string& path) const {
  const double d = Number(v, path);
  if (!(d > 0)) Fail(path, v, "must be > 0");
  return d;
}
double FieldReader::NonNegative(const json& v, const std::string& path) const {
  const double d = Number(v, path);
  if (!(d >= 0)) Fail(path, v, "must be >= 0");
  return d;
}
double FieldReader::InRange(const json& v, const std::string& path, double lo_exclusive, double hi_inclusive) const {
  const double d = Number(v, path);
  if (!(d > lo_exclusive && d <= hi_inclusive))
    Fail(path, v, "must be in (" + NumberText(lo_exclusive) + ", " + NumberText(hi_inclusive) + "]");
  return d;
}

double FieldReader::Coordinate(const json& v, const std::string& path) const {
  const double d = Number(v, path);
  if (!(std::abs(d) <= internal::kMaxCoordinate))
    Fail(path, v, "|coordinate| must be <= " + internal::FormatNumber(internal::kMaxCoordinate) + " (precision limit)");
  return d;
}
double FieldReader::PositiveLength(const json& v, const std::string& path) const {
  Positive(v, path);
  return Coordinate(v, path);
}
Eigen::Vector2d FieldReader::Point(const json& v, const std::string& path) const {
  const Eigen::Vector2d p = Vector<2>(v, path);
  for (std::size_t i = 0; i < 2; ++i) Coordinate(v[i], Index(path, i));
  return p;
}
double FieldReader::InClosedRange(const json& v, const std::string& path, double lo, double hi) const {
  const double d = Number(v, path);
  if (!(d >= lo && d <= hi))
    Fail(path, v, "must be in [" + internal::FormatNumber(lo) + ", " + internal::FormatNumber(hi) + "]");
  return d;
}

long long FieldReader::Integer(const json& v, const std::string& path, long long lo, long long hi) const {
  long long n = 0;
  if (v.is_number_integer() && !v.is_number_unsigned()) {
    n = v.get<std::int64_t>();
  } else if (v.is_number_unsigned()) {
    const std::uint64_t u = v.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(hi)) Fail(path, v, "must be <= " + std::to_string(hi));
    n = static_cast<long long>(u);
  } else if (v.is_number_float()) {
    const double d = v.get<double>();
    if (!std::isfinite(d) || std::floor(d) != d) Fail(path, v, "must be an integer");
    if (d < static_cast<double>(lo)) Fail(path, v, "must be >= " + std::to_string(lo));
    if (d > static_cast<double>(hi)) Fail(path, v, "must be <= " + std::to_string(hi));
    n = static_cast<long long>(d);
  } else {
    Fail(path, v, "must be an integer");
  }
  if (n < lo) Fail(path, v, "must be >= " + std::to_string(lo));
  if (n > hi) Fail(path, v, "must be <= " + std::to_string(hi));
  return n;
}

std::uint64_t FieldReader::Seed(const json& v, const std::string& path) const {
  if (v.is_number_unsigned()) return v.get<std::uint64_t>();
  if (v.is_number_integer()) Fail(path, v, "must be a non-negative integer");
  if (v.is_number_float()) {
    const double d = v.get<double>();
    if (std::isfinite(d) && std::floor(d) == d && d >= 0 && d < 18446744073709551616.0)
      return static_cast<std::uint64_t>(d);
  }
  Fail(path, v, "must be a non-negative integer");
}

std::string FieldReader::String(const json& v, const std::string& path) const {
  if (!v.is_string()) Fail(path, v, "must be a string");
  return v.get<std::string>();
}

const json& FieldReader::Array(const json& v, const std::string& path, long long min_size, long long max_size) const {
  if (!v.is_array()) Fail(path, v, "must be an array");
  const long long n = static_cast<long long>(v.size());
  if (n < min_size) Fail(path, v, "must have at least " + std::to_string(min_size) + " element(s)");
  if (n > max_size) Fail(path, v, "must have at most " + std::to_string(max_size) + " elements");
  return v;
}

std::vector<Eigen::Vector2d> FieldReader::Points(const json& v,
                                                 const std::string& path,
                                                 long long min_size,
                                                 long long max_size) const {
  Array(v, path, min_size, max_size);
  std::vector<Eigen::Vector2d> out;
  out.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out.push_back(Point(v[i], Index(path, i)));
  return out;
}

double FieldReader::Tolerance(const json& v, const std::string& path) const {
  const double d = Number(v, path);
  if (!(d >= internal::kMinTolerance && d < 1)) Fail(path, v, "must be in [1e-15, 1)");
  return d;
}

bool FieldReader::Boolean(const json& v, const std::string& path) const {
  if (!v.is_boolean()) Fail(path, v, "must be true or false");
  return v.get<bool>();
}

}  // namespace plateball::internal::problem_io
