// Input checks shared by the library: every failure names the field and the value.
#pragma once

#include <Eigen/Core>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace plateball::internal {

/// Shortest text that reads back as the same double ("0.1", "1e+200", "nan", "-inf").
inline std::string FormatNumber(double value) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof(buf), value);
  return std::string(buf, res.ptr);
}

[[noreturn]] inline void ThrowInvalid(const std::string& field, double value, const std::string& bound) {
  throw std::invalid_argument("'" + field + "' = " + FormatNumber(value) + " is invalid: " + bound);
}

inline void RequireFinite(const std::string& field, double v) {
  if (!std::isfinite(v)) ThrowInvalid(field, v, "must be finite");
}
inline void RequirePositive(const std::string& field, double v) {
  if (!(std::isfinite(v) && v > 0)) ThrowInvalid(field, v, "must be finite and > 0");
}
inline void RequireNonNegative(const std::string& field, double v) {
  if (!(std::isfinite(v) && v >= 0)) ThrowInvalid(field, v, "must be finite and >= 0");
}
template <typename Derived>
inline void RequireFinite(const std::string& field, const Eigen::MatrixBase<Derived>& m) {
  const auto e = m.eval();
  for (Eigen::Index i = 0; i < e.size(); ++i)
    if (!std::isfinite(e.data()[i])) ThrowInvalid(field + "[" + std::to_string(i) + "]", e.data()[i], "must be finite");
}

}  // namespace plateball::internal
