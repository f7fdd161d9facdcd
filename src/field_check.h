// The ranges of a field list (plateball/field_list.h) checked in list order, for the options'
// Validate(): the first value out of its range as the library's message "FIELD: value V: must
// be ...", from the same list as the Python attributes and the problem files' readers. Fields
// without a number or count range (nested options, booleans) are left to Validate() itself.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

#include "check.h"
#include "plateball/field_list.h"

namespace plateball::internal {

/// The archive: see the header comment.
class RangeCheck {
 public:
  /// `prefix` is put before each field name ("tolerances.").
  explicit RangeCheck(std::string prefix) : prefix_(std::move(prefix)) {}

  template <class... T>
  void Visit(const FieldSpec<T>&... f) {
    (Check(f), ...);
  }
  /// Empty when every field is in its range.
  const std::string& message() const { return message_; }

 private:
  template <class T>
  void Check(const FieldSpec<T>& f) {
    if (!message_.empty()) return;
    if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool> && std::is_signed_v<T>) {
      const long long v = *f.value;
      if (v >= f.min_count && v <= f.max_count) return;
      const bool unbounded = f.max_count == static_cast<long long>(std::numeric_limits<T>::max());
      message_ = InvalidValueMessage(
          prefix_ + f.name,
          *f.value,
          unbounded ? "must be >= " + std::to_string(f.min_count)
                    : "must be in [" + std::to_string(f.min_count) + ", " + std::to_string(f.max_count) + "]");
    } else if constexpr (std::is_floating_point_v<T>) {
      const std::string what = NumberProblem(f, *f.value);
      if (!what.empty()) message_ = InvalidValueMessage(prefix_ + f.name, *f.value, what);
    }
  }

  // What is wrong with v under the field's check; empty when nothing.
  static std::string NumberProblem(const FieldSpec<double>& f, double v) {
    switch (f.check) {
      case FieldCheck::kFinite:
        return std::isfinite(v) ? "" : "must be finite";
      case FieldCheck::kPositive:
        return std::isfinite(v) && v > 0 ? "" : "must be finite and > 0";
      case FieldCheck::kNonNegative:
        if (!std::isfinite(f.upper)) return std::isfinite(v) && v >= 0 ? "" : "must be finite and >= 0";
        return v >= 0 && v <= f.upper
                   ? ""
                   : "must be in [0, " + BoundText(f.upper) + "]" + (f.hint ? std::string(" (") + f.hint + ")" : "");
      case FieldCheck::kTolerance:
        return v >= f.lower && v < f.upper ? "" : "must be in [" + BoundText(f.lower) + ", " + BoundText(f.upper) + ")";
      case FieldCheck::kClosed:
        return v >= f.lower && v <= f.upper ? ""
                                            : "must be in [" + BoundText(f.lower) + ", " + BoundText(f.upper) + "]";
    }
    return "";
  }

  std::string prefix_;
  std::string message_;
};

/// The first field of `value`'s list out of its range, as "PREFIXFIELD: value V: must be ...";
/// empty when all are in range.
template <class S>
std::string CheckRanges(const S& value, std::string prefix = "") {
  RangeCheck check(std::move(prefix));
  // Serialize only takes the members' addresses; the check reads through them.
  const_cast<S&>(value).Serialize(&check);
  return check.message();
}

}  // namespace plateball::internal
