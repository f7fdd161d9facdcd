// Input checks shared by the library: every failure names the field and the value, in one
// format built by InvalidValueMessage: "FIELD: value V: what is wrong" (V in shortest round-trip
// form). The problem-file reader prefixes the file name ("figure7.json: initial.mu: value -1: ...").
#pragma once

#include <Eigen/Core>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "plateball/limits.h"

namespace plateball::internal {

/// Shortest text that reads back as the same double ("0.1", "1e+200", "nan", "-inf").
inline std::string FormatNumber(double value) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof(buf), value);
  return std::string(buf, res.ptr);
}

/// A bound in a message: the shorter of the plain and the exponent form ("1e6", not "1e+06").
inline std::string BoundText(double v) {
  const std::string plain = FormatNumber(v);
  const std::size_t e = plain.find('e');
  if (e == std::string::npos) return plain;
  std::string exponent = plain.substr(e + 1);
  const bool negative = exponent[0] == '-';
  if (exponent[0] == '+' || negative) exponent.erase(0, 1);
  while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
  return plain.substr(0, e) + "e" + (negative ? "-" : "") + exponent;
}

/// The one message for an invalid value: "FIELD: value V: WHAT".
inline std::string InvalidValueMessage(const std::string& field,
                                       const std::string& value_text,
                                       const std::string& what) {
  return field + ": value " + value_text + ": " + what;
}
inline std::string InvalidValueMessage(const std::string& field, double value, const std::string& what) {
  return InvalidValueMessage(field, FormatNumber(value), what);
}
/// Counts print as integers ("1000000", not "1e+06").
template <typename Int, std::enable_if_t<std::is_integral_v<Int>, int> = 0>
std::string InvalidValueMessage(const std::string& field, Int value, const std::string& what) {
  return InvalidValueMessage(field, std::to_string(value), what);
}

[[noreturn]] inline void ThrowInvalid(const std::string& field,
                                      const std::string& value_text,
                                      const std::string& what) {
  throw std::invalid_argument(InvalidValueMessage(field, value_text, what));
}
[[noreturn]] inline void ThrowInvalid(const std::string& field, double value, const std::string& what) {
  throw std::invalid_argument(InvalidValueMessage(field, value, what));
}
template <typename Int, std::enable_if_t<std::is_integral_v<Int>, int> = 0>
[[noreturn]] void ThrowInvalid(const std::string& field, Int value, const std::string& what) {
  throw std::invalid_argument(InvalidValueMessage(field, value, what));
}

/// Throws the message of a Validate() function when it is not empty.
inline void ThrowIfInvalid(const std::string& message) {
  if (!message.empty()) throw std::invalid_argument(message);
}

// The checks below take the field name as given (a literal stays a `const char*`), so that the
// std::string of the message is built only for a bad value: they run on every join and impulse.
template <typename Field>
inline void RequireFinite(const Field& field, double v) {
  if (!std::isfinite(v)) ThrowInvalid(field, v, "must be finite");
}
template <typename Field>
inline void RequirePositive(const Field& field, double v) {
  if (!(std::isfinite(v) && v > 0)) ThrowInvalid(field, v, "must be finite and > 0");
}
template <typename Field>
inline void RequireNonNegative(const Field& field, double v) {
  if (!(std::isfinite(v) && v >= 0)) ThrowInvalid(field, v, "must be finite and >= 0");
}
/// lo <= v <= hi (both finite), with the range named in the message.
template <typename Field>
inline void RequireInRange(const Field& field, double v, double lo, double hi) {
  if (!(v >= lo && v <= hi)) ThrowInvalid(field, v, "must be in [" + FormatNumber(lo) + ", " + FormatNumber(hi) + "]");
}
template <typename Derived>
inline void RequireFinite(const std::string& field, const Eigen::MatrixBase<Derived>& m) {
  const auto e = m.eval();
  for (Eigen::Index i = 0; i < e.size(); ++i)
    if (!std::isfinite(e.data()[i])) ThrowInvalid(field + "[" + std::to_string(i) + "]", e.data()[i], "must be finite");
}

// ------------------------------------------------------------------ documented input ranges
// Beyond these the double arithmetic of the solvers loses the digits the answer needs (README,
// "Limits"); each is checked where the value enters the library.
constexpr double kMaxCoordinate = limits::kMaxCoordinate;  ///< |x|, |y| of positions and targets (limits.h)
constexpr double kMinLambda = 1e-3;                        ///< lambda: stiffness and drift beyond these
constexpr double kMaxLambda = 1e3;
constexpr double kMinMu = 1e-12;  ///< energy mu
constexpr double kMaxMu = 1e12;
constexpr double kMinTolerance = 1e-15;  ///< integration tolerances

// Sizes that drive the work (README, "Limits"): each keeps one call under ~10 s and ~1 GB.
constexpr int kMaxPartitionSteps = limits::kMaxPartitionSteps;  ///< partition n, impulses of a plan (limits.h)
constexpr int kMaxSamples = limits::kMaxSamples;  ///< samples of a simulation, path sample points (limits.h)
constexpr double kMaxIsoparallelChord = 40;       ///< |goal - start| of the isoparallel problem
constexpr double kMaxStartsTimesChord = 3.5e5;  ///< multi-start: starts x |goal - start| (default 8192 x chord 40 fits)
constexpr double kMaxLengthCapFactor = 10;      ///< family search (= IsoparallelOptions::kMaxLengthCapFactor)

/// 1 <= n <= hi for a count.
inline void RequireCount(const std::string& field, long long n, long long hi) {
  if (!(n >= 1 && n <= hi)) ThrowInvalid(field, n, "must be in [1, " + std::to_string(hi) + "]");
}

/// |v| <= kMaxCoordinate for a coordinate (finite first).
inline void RequireCoordinate(const std::string& field, double v) {
  RequireFinite(field, v);
  if (!(std::abs(v) <= kMaxCoordinate))
    ThrowInvalid(field, v, "|coordinate| must be <= " + FormatNumber(kMaxCoordinate) + " (precision limit)");
}
template <typename Derived>
inline void RequireCoordinates(const std::string& field, const Eigen::MatrixBase<Derived>& m) {
  const auto e = m.eval();
  for (Eigen::Index i = 0; i < e.size(); ++i)  // the element name is built only for a bad value (hot path)
    if (!(std::abs(e.data()[i]) <= kMaxCoordinate))
      RequireCoordinate(field + "[" + std::to_string(i) + "]", e.data()[i]);
}
/// mu in [kMinMu, kMaxMu].
template <typename Field>
inline void RequireEnergy(const Field& field, double mu) {
  RequirePositive(field, mu);
  RequireInRange(field, mu, kMinMu, kMaxMu);
}

}  // namespace plateball::internal
