// One list of a struct's fields, declared once in the struct:
//
//   template <class Archive>
//   void Serialize(Archive* a) {
//     a->Visit(PLATEBALL_FIELD(max_impulses, "largest count searched").Counts(1, kMaxImpulses),
//              PLATEBALL_FIELD(max_total_time, "search window; 0: automatic").NonNegative());
//   }
//
// A field the archives cannot express (a nested object, a field present only with another) is
// listed ByHand(): its key keeps its place, and the section's own code reads and writes it.
//
// Each field is a name, a pointer to the value, a documentation line and the range a problem file
// enforces. Archives walk the list: the problem-file section reader and writer and the section's
// input-schema fragment (src/problem_io/field_archive.h). This is the name-value pattern of
// Drake's Serialize(Archive*). Pure C++: no JSON types here.
#pragma once

#include <limits>
#include <type_traits>

namespace plateball {

/// The range a problem file enforces on a number field: the reader's message and the schema's
/// bounds both follow from it. Integer fields use FieldSpec::Counts instead.
enum class FieldCheck {
  kFinite,       ///< any finite number
  kPositive,     ///< > 0
  kNonNegative,  ///< >= 0, and <= `upper` when it is finite
  kTolerance,    ///< in [1e-15, 1): below, the step size underflows in double precision
  kClosed,       ///< in [lower, upper]
};

/// One named field of a struct: see the header comment.
template <class T>
struct FieldSpec {
  const char* name;
  T* value;
  const char* doc;
  FieldCheck check = FieldCheck::kFinite;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  /// Integer fields: [min_count, max_count]; the type's largest value means no upper bound.
  long long min_count = std::numeric_limits<long long>::min();
  long long max_count = std::numeric_limits<long long>::max();
  /// Said after an out-of-range message and in the schema, e.g. "0: automatic".
  const char* hint = nullptr;
  /// false: a library option that a problem file does not set.
  bool in_file = true;
  /// true: the section's own code reads, writes and describes the field (a nested object, or a
  /// field whose presence depends on another); the archives only admit its key in list order.
  bool by_hand = false;
  /// true: `unset` means "no limit" and the writer leaves the field out when the value equals it.
  bool omittable = false;
  T unset{};

  /// An integer in [lo, hi].
  FieldSpec& Counts(long long lo, long long hi = static_cast<long long>(std::numeric_limits<T>::max())) {
    static_assert(std::is_integral_v<T> && !std::is_same_v<T, bool>, "Counts() is for integer fields");
    min_count = lo;
    max_count = hi;
    return *this;
  }
  FieldSpec& Positive() { return Check(FieldCheck::kPositive, 0.0, upper); }  ///< A number > 0.
  FieldSpec& NonNegative(double hi = std::numeric_limits<double>::infinity(), const char* why = nullptr) {
    hint = why;
    return Check(FieldCheck::kNonNegative, 0.0, hi);
  }
  FieldSpec& Tolerance() {
    return Check(FieldCheck::kTolerance, 1e-15, 1.0);
  }  ///< An integration tolerance, in [1e-15, 1).
  FieldSpec& Closed(double lo, double hi) { return Check(FieldCheck::kClosed, lo, hi); }  ///< A number in [lo, hi].
  FieldSpec& NotInFile() {
    in_file = false;
    return *this;
  }
  FieldSpec& ByHand() {
    by_hand = true;
    return *this;
  }
  FieldSpec& OmittedAt(T value) {
    omittable = true;
    unset = value;
    return *this;
  }

 private:
  FieldSpec& Check(FieldCheck c, double lo, double hi) {
    static_assert(std::is_floating_point_v<T>, "number checks are for floating-point fields");
    check = c;
    lower = lo;
    upper = hi;
    return *this;
  }
};

/// The field `name` of value `*value`, documented by `doc` (one line, no trailing period).
template <class T>
FieldSpec<T> MakeFieldSpec(const char* name, T* value, const char* doc) {
  return FieldSpec<T>{name, value, doc};
}

}  // namespace plateball

/// A field of the struct whose Serialize() lists it, named as the member.
#define PLATEBALL_FIELD(member, doc) ::plateball::MakeFieldSpec(#member, &(member), doc)

/// \fn plateball::FieldSpec::NonNegative(double hi, const char *why)
/// A number >= 0, and <= `hi` when finite; `why` is said after an out-of-range message.

/// \fn plateball::FieldSpec::NotInFile()
/// A library option that a problem file does not set (the section reader rejects its key).

/// \fn plateball::FieldSpec::ByHand()
/// A field the section's own code reads, writes and describes (a nested object, or a field that
/// depends on another); the archives only admit its key, in list order.

/// \fn plateball::FieldSpec::OmittedAt(T value)
/// `value` means "not set" (an infinite bound, a zero interval): the writer leaves the field out
/// when it holds it, and a file without the field keeps it.
