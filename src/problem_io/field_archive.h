// The archives of a field list (plateball/field_list.h) for problem files: the section reader
// (closed key set, the ranges of each field, the FieldReader's messages), the section writer and
// the section's input-schema fragment (compared with schemas/input/ by field_list_test).
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "check.h"
#include "plateball/field_list.h"
#include "problem_io/field_reader.h"
#include "problem_io/value_text.h"

namespace plateball::internal::problem_io {

/// A finite number for the writer, else "WriteProblemJson: PATH: value V: must be finite".
inline double WrittenNumber(const std::string& path, double v) {
  if (!std::isfinite(v))
    throw std::invalid_argument("WriteProblemJson: " + path + ": value " + NumberText(v) + ": must be finite");
  return v;
}

/// Reads one section into a struct: `value.Serialize(&reader)`. Keys outside the list's file
/// fields (and the caller's `leading` keys) are an error; each field present is checked and
/// stored, absent ones keep their value; ByHand fields are left to the caller.
class SectionReader {
 public:
  SectionReader(const FieldReader& r, const json& j, std::string path, std::vector<const char*> leading = {})
      : r_(r), j_(j), path_(std::move(path)), leading_(std::move(leading)) {}

  template <class... T>
  void Visit(const FieldSpec<T>&... f) {
    std::vector<const char*> keys = leading_;
    ((f.in_file ? keys.push_back(f.name) : void()), ...);
    r_.Object(j_, path_, keys);
    (Read(f), ...);
  }

 private:
  template <class T>
  void Read(const FieldSpec<T>& f) const {
    if (!f.in_file || f.by_hand) return;
    const json* v = FieldReader::Find(j_, f.name);
    if (!v) return;
    const std::string path = FieldReader::Join(path_, f.name);
    if constexpr (std::is_same_v<T, bool>) {
      *f.value = r_.Boolean(*v, path);
    } else if constexpr (std::is_integral_v<T>) {
      *f.value = static_cast<T>(r_.Integer(*v, path, f.min_count, f.max_count));
    } else if constexpr (std::is_floating_point_v<T>) {
      *f.value = Number(*v, path, f);
    } else {
      throw std::logic_error(path + ": a problem file has no form for this field");
    }
  }

  double Number(const json& v, const std::string& path, const FieldSpec<double>& f) const {
    switch (f.check) {
      case FieldCheck::kFinite:
        return r_.Number(v, path);
      case FieldCheck::kPositive:
        return r_.Positive(v, path);
      case FieldCheck::kTolerance:
        return r_.Tolerance(v, path);
      case FieldCheck::kClosed:
        return r_.InClosedRange(v, path, f.lower, f.upper);
      case FieldCheck::kNonNegative: {
        const double d = r_.NonNegative(v, path);
        if (d > f.upper)
          r_.Fail(
              path, v, "must be in [0, " + BoundText(f.upper) + "]" + (f.hint ? std::string(" (") + f.hint + ")" : ""));
        return d;
      }
    }
    return r_.Number(v, path);
  }

  const FieldReader& r_;
  const json& j_;
  std::string path_;
  std::vector<const char*> leading_;
};

/// Writes a section's file fields in list order, numbers checked finite; a field at its
/// OmittedAt value is left out, a ByHand field is written by `by_hand(name, &section)` in its place.
class SectionWriter {
 public:
  using HandWriter = std::function<void(const std::string& name, ojson* section)>;
  explicit SectionWriter(std::string path, HandWriter by_hand = nullptr)
      : path_(std::move(path)), by_hand_(std::move(by_hand)) {}

  template <class... T>
  void Visit(const FieldSpec<T>&... f) {
    (Write(f), ...);
  }
  const ojson& section() const { return out_; }

 private:
  template <class T>
  void Write(const FieldSpec<T>& f) {
    if (!f.in_file) return;
    if (f.by_hand) {
      if (!by_hand_) throw std::logic_error(path_ + "." + f.name + ": no writer for this field");
      by_hand_(f.name, &out_);
      return;
    }
    if constexpr (std::is_arithmetic_v<T>) {
      if (f.omittable && *f.value == f.unset) return;
      if constexpr (std::is_floating_point_v<T>)
        out_[f.name] = WrittenNumber(path_ + "." + f.name, *f.value);
      else
        out_[f.name] = *f.value;
    } else {
      throw std::logic_error(path_ + "." + f.name + ": a problem file has no form for this field");
    }
  }

  std::string path_;
  HandWriter by_hand_;
  ojson out_ = ojson::object();
};

/// The JSON-schema fragment of a section: its file fields with type, bounds and description
/// (ByHand fields are described in the committed schema by hand).
class SectionSchema {
 public:
  template <class... T>
  void Visit(const FieldSpec<T>&... f) {
    (Describe(f), ...);
  }
  /// {"type": "object", "properties": ..., "required": [], "additionalProperties": false}
  ojson Fragment() const {
    return ojson{
        {"type", "object"}, {"properties", properties_}, {"required", ojson::array()}, {"additionalProperties", false}};
  }

 private:
  template <class T>
  void Describe(const FieldSpec<T>& f) {
    if (!f.in_file || f.by_hand) return;
    ojson p;
    if constexpr (std::is_same_v<T, bool>) {
      p["type"] = "boolean";
    } else if constexpr (std::is_integral_v<T>) {
      p["type"] = "integer";
      p["minimum"] = f.min_count;
      if (f.max_count < static_cast<long long>(std::numeric_limits<T>::max())) p["maximum"] = f.max_count;
    } else if constexpr (std::is_floating_point_v<T>) {
      p["type"] = "number";
      Bounds(f, &p);
    } else {
      throw std::logic_error(std::string(f.name) + ": a problem file has no form for this field");
    }
    p["description"] = f.hint ? std::string(f.doc) + "; " + f.hint : std::string(f.doc);
    properties_[f.name] = p;
  }
  static void Bounds(const FieldSpec<double>& f, ojson* p) {
    switch (f.check) {
      case FieldCheck::kFinite:
        return;
      case FieldCheck::kPositive:
        (*p)["exclusiveMinimum"] = 0;
        return;
      case FieldCheck::kTolerance:
        (*p)["minimum"] = f.lower;
        (*p)["exclusiveMaximum"] = 1;
        return;
      case FieldCheck::kNonNegative:
      case FieldCheck::kClosed:
        (*p)["minimum"] = f.lower;
        if (std::isfinite(f.upper)) (*p)["maximum"] = f.upper;
        return;
    }
  }

  ojson properties_ = ojson::object();
};

/// Reads `*value` from section `j` at `path` by its field list; `leading`: keys of the section
/// that are not the struct's fields (the caller reads them), admitted before the list's.
template <class S>
void ReadSection(
    const FieldReader& r, const json& j, const std::string& path, S* value, std::vector<const char*> leading = {}) {
  SectionReader reader(r, j, path, std::move(leading));
  value->Serialize(&reader);
}

/// The section of `value` by its field list; `by_hand` writes the ByHand fields.
template <class S>
ojson WriteSection(const S& value, const std::string& path, SectionWriter::HandWriter by_hand = nullptr) {
  SectionWriter writer(path, std::move(by_hand));
  // Serialize only takes the members' addresses; the writer reads through them (as Drake's
  // YamlWriteArchive does with its const_cast).
  const_cast<S&>(value).Serialize(&writer);
  return writer.section();
}

/// The schema fragment of a struct's section.
template <class S>
ojson SchemaOfSection() {
  S value{};
  SectionSchema schema;
  value.Serialize(&schema);
  return schema.Fragment();
}

}  // namespace plateball::internal::problem_io
