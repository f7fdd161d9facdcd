// The positional numeric arguments of the measuring programs (separatrix_measure, loops_measure).
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace plateball::bench {

/// Argument i as a number in [lo, hi], or `fallback` when absent. Throws std::invalid_argument
/// naming the argument and its value when it is not a number in range.
inline double PositionalNumber(int argc, char** argv, int i, double lo, double hi, double fallback) {
  if (i >= argc) return fallback;
  std::size_t used = 0;
  const std::string text = argv[i];
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !(v >= lo && v <= hi)) {
    std::ostringstream message;
    message << "argument " << i << ": value " << text << ": expected a number in [" << lo << ", " << hi << "]";
    throw std::invalid_argument(message.str());
  }
  return v;
}

}  // namespace plateball::bench
