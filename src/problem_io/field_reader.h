// The problem reader's checked accessors for single values (numbers, integers, points,
// orientations, objects with a closed key set). Every failure throws std::invalid_argument
// "SOURCE: FIELD: value V: what is wrong"; the section readers (section_readers.h) are built on it.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "problem_io/value_text.h"

namespace plateball::internal::problem_io {

/// Shown as the value of a required field that is missing.
inline const char* const kMissing = "(missing)";

class FieldReader {
 public:
  /// `source` names the file (or standard input, or a string) in every message.
  explicit FieldReader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& path, const std::string& value, const std::string& what) const;
  [[noreturn]] void Fail(const std::string& path, const char* value, const std::string& what) const;
  [[noreturn]] void Fail(const std::string& path, const json& value, const std::string& what) const;

  /// An object whose keys are all in `allowed`.
  void Object(const json& j, const std::string& path, const std::vector<const char*>& allowed) const;

  static std::string Join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  static std::string Index(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

  /// Member lookup; nullptr when absent.
  static const json* Find(const json& obj, const char* key) {
    const auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
  }
  const json& Require(const json& obj, const std::string& path, const char* key) const;

  double Number(const json& v, const std::string& path) const;
  double Positive(const json& v, const std::string& path) const;
  double NonNegative(const json& v, const std::string& path) const;
  double InRange(const json& v, const std::string& path, double lo_exclusive, double hi_inclusive) const;
  double InClosedRange(const json& v, const std::string& path, double lo, double hi) const;
  /// A coordinate or a length on the plate: |v| <= internal::kMaxCoordinate (the Limits table).
  double Coordinate(const json& v, const std::string& path) const;
  double PositiveLength(const json& v, const std::string& path) const;
  Eigen::Vector2d Point(const json& v, const std::string& path) const;
  /// A tolerance in [1e-15, 1): below, the step size underflows in double precision.
  double Tolerance(const json& v, const std::string& path) const;
  /// An integer in [lo, hi]; a float with an integral value is accepted.
  long long Integer(const json& v, const std::string& path, long long lo, long long hi) const;
  std::uint64_t Seed(const json& v, const std::string& path) const;
  std::string String(const json& v, const std::string& path) const;
  bool Boolean(const json& v, const std::string& path) const;

  /// An array of `N` finite numbers.
  template <int N>
  Eigen::Matrix<double, N, 1> Vector(const json& v, const std::string& path) const {
    if (!v.is_array() || v.size() != static_cast<std::size_t>(N))
      Fail(path, v, "must be an array of " + std::to_string(N) + " numbers");
    Eigen::Matrix<double, N, 1> out;
    for (int i = 0; i < N; ++i)
      out(i) = Number(v[static_cast<std::size_t>(i)], Index(path, static_cast<std::size_t>(i)));
    return out;
  }

  const json& Array(const json& v, const std::string& path, long long min_size, long long max_size) const;
  std::vector<Eigen::Vector2d> Points(const json& v,
                                      const std::string& path,
                                      long long min_size,
                                      long long max_size) const;

  /// An orientation in one of three forms: quaternion, matrix or axis_angle (orientation_reader.cc).
  Eigen::Matrix3d Orientation(const json& j, const std::string& path) const;

  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

}  // namespace plateball::internal::problem_io
