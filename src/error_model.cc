#include "plateball/error_model.h"

#include <array>
#include <charconv>
#include <cmath>
#include <set>
#include <string>

#include "check.h"

namespace plateball {
namespace {

struct ErrorField {
  const char* name;
  double ErrorModel::*member;
  double max;
};

constexpr std::array<ErrorField, 8> kFields{{
    {"impulse_magnitude", &ErrorModel::impulse_magnitude, ErrorModel::kMaxImpulseMagnitude},
    {"impulse_angle", &ErrorModel::impulse_angle, ErrorModel::kMaxImpulseAngle},
    {"timing", &ErrorModel::timing, ErrorModel::kMaxTiming},
    {"energy_loss", &ErrorModel::energy_loss, ErrorModel::kMaxEnergyLoss},
    {"lambda", &ErrorModel::lambda, ErrorModel::kMaxLambda},
    {"observation", &ErrorModel::observation, ErrorModel::kMaxObservation},
    {"pulse_duration", &ErrorModel::pulse_duration, ErrorModel::kMaxPulseDuration},
    {"pulse_causal", &ErrorModel::pulse_causal, 1.0},
}};

std::string RangeText(double max) { return "must be a number in [0, " + internal::FormatNumber(max) + "]"; }

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// One KEY=VALUE item into `model`.
void ParseItem(const std::string& item, const std::string& field, std::set<std::string>* seen, ErrorModel* model) {
  const auto eq = item.find('=');
  if (eq == std::string::npos)
    internal::ThrowInvalid(field,
                           "'" + item + "'",
                           "expected KEY=VALUE (keys: impulse_magnitude, impulse_angle, "
                           "timing, energy_loss, lambda, observation, pulse_duration, pulse_causal)");
  const std::string key = Trim(item.substr(0, eq));
  const std::string value = Trim(item.substr(eq + 1));
  for (const ErrorField& f : kFields) {
    if (key != f.name) continue;
    const std::string name = ErrorModelKeyField(field, key);
    if (!seen->insert(key).second) internal::ThrowInvalid(name, "'" + value + "'", "given twice");
    double v = 0.0;
    const auto res = std::from_chars(value.data(), value.data() + value.size(), v);
    if (value.empty() || res.ec != std::errc() || res.ptr != value.data() + value.size())
      internal::ThrowInvalid(name, "'" + value + "'", RangeText(f.max));
    if (!(v >= 0.0 && v <= f.max)) internal::ThrowInvalid(name, v, RangeText(f.max));
    if (f.member == &ErrorModel::pulse_causal && v != 0.0 && v != 1.0)
      internal::ThrowInvalid(name, v, "must be 0 (centred pulses) or 1 (causal pulses)");
    model->*f.member = v;
    return;
  }
  internal::ThrowInvalid(field,
                         "'" + key + "'",
                         "unknown error model (keys: impulse_magnitude, impulse_angle, "
                         "timing, energy_loss, lambda, observation, pulse_duration, "
                         "pulse_causal)");
}

}  // namespace

std::string ErrorModel::Validate() const {
  for (const ErrorField& f : kFields) {
    const double v = this->*f.member;
    if (!(v >= 0.0 && v <= f.max)) return internal::InvalidValueMessage(f.name, v, RangeText(f.max));
  }
  if (pulse_causal != 0.0 && pulse_causal != 1.0)
    return internal::InvalidValueMessage(
        "pulse_causal", pulse_causal, "must be 0 (centred pulses) or 1 (causal pulses)");
  return "";
}

bool ErrorModel::IsZero() const {
  for (const ErrorField& f : kFields)
    if (this->*f.member != 0.0) return false;
  return true;
}

std::string ToString(const ErrorModel& model) {
  std::string out;
  for (const ErrorField& f : kFields) {
    if (model.*f.member == 0.0) continue;
    if (!out.empty()) out += ",";
    out += std::string(f.name) + "=" + internal::FormatNumber(model.*f.member);
  }
  return out.empty() ? "none" : out;
}

std::string ErrorModelKeyField(const std::string& field, const std::string& key) {
  const auto word = field.find_last_of(" ");
  const bool option = field.compare(word == std::string::npos ? 0 : word + 1, 2, "--") == 0;
  return field + (option ? " " : ".") + key;
}

ErrorModel ParseErrorModel(const std::string& text, const std::string& field) {
  ErrorModel model;
  const std::string all = Trim(text);
  if (all.empty() || all == "none") return model;
  std::set<std::string> seen;
  std::size_t begin = 0;
  while (begin <= all.size()) {
    const std::size_t end = std::min(all.find(',', begin), all.size());
    ParseItem(Trim(all.substr(begin, end - begin)), field, &seen, &model);
    begin = end + 1;
  }
  return model;
}

}  // namespace plateball
