// Input checks shared by the library: every failure names the field and the value.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace plateball::internal {

[[noreturn]] inline void ThrowInvalid(const std::string& field, double value, const std::string& bound) {
  std::ostringstream os;
  os.precision(17);
  os << "'" << field << "' = " << value << " is invalid: " << bound;
  throw std::invalid_argument(os.str());
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
