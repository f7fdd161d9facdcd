// The numeric arguments of the measuring programs (certify_measure's options, the positional ones
// of separatrix_measure and loops_measure).
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace plateball::bench {

/// `text` as a number in [lo, hi]. Throws std::invalid_argument "NAME: value TEXT: expected a
/// number in [lo, hi]" when it is not one (or has trailing characters).
inline double ParseNumber(const std::string& name, const std::string& text, double lo, double hi) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !(v >= lo && v <= hi)) {
    std::ostringstream message;
    message << name << ": value " << text << ": expected a number in [" << lo << ", " << hi << "]";
    throw std::invalid_argument(message.str());
  }
  return v;
}

/// Argument i as a number in [lo, hi], or `fallback` when absent. Throws std::invalid_argument
/// naming the argument and its value when it is not a number in range.
inline double PositionalNumber(int argc, char** argv, int i, double lo, double hi, double fallback) {
  return i >= argc ? fallback : ParseNumber("argument " + std::to_string(i), argv[i], lo, hi);
}

}  // namespace plateball::bench
