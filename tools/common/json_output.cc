#include "common/json_output.h"

#include <cmath>
#include <stdexcept>

#include "common/output_file.h"
#include "plateball/so3.h"
#include "plateball/version.h"

namespace plateball::tools {

Json ToJson(const Eigen::Vector2d& v) { return Json::array({v.x(), v.y()}); }
Json ToJson(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }
Json ToJson(const Eigen::Matrix3d& m) {
  Json rows = Json::array();
  for (int i = 0; i < 3; ++i) rows.push_back(Json::array({m(i, 0), m(i, 1), m(i, 2)}));
  return rows;
}
Json ToJson(const std::vector<Eigen::Vector2d>& points) {
  Json a = Json::array();
  for (const auto& p : points) a.push_back(ToJson(p));
  return a;
}
Json ToJson(const AngleState& a) { return Json{{"theta", a.theta}, {"phi", a.phi}, {"psi", a.psi}}; }
Json ToJson(const BallModel& m) {
  Json j{{"lambda", m.lambda()}};
  if (m.has_inertia()) {
    j["alpha"] = m.alpha();
    j["beta"] = m.beta();
  }
  j["realisable"] = m.IsRealisable();
  return j;
}
Json ToJson(const MotionSample& s) {
  return Json{{"t", s.t},
              {"angles", ToJson(s.angles)},
              {"z", ToJson(s.state.z)},
              {"x", ToJson(s.x)},
              {"orientation", ToJson(s.A)},
              {"omega", ToJson(s.state.omega)},
              {"energy", s.energy}};
}
Json RotationToJson(const Eigen::Matrix3d& r) {
  const Eigen::Vector3d w = LogSO3(r);
  Json j{{"matrix", ToJson(r)}, {"rotation_vector", ToJson(w)}, {"angle", w.norm()}};
  if (w.norm() > 0) j["axis"] = ToJson(Eigen::Vector3d(w / w.norm()));
  return j;
}

std::string ProblemName(const Problem& p) {
  if (!p.name.empty()) return p.name;
  std::string base =
      p.source.substr(p.source.find_last_of('/') == std::string::npos ? 0 : p.source.find_last_of('/') + 1);
  if (base.size() > 5 && base.compare(base.size() - 5, 5, ".json") == 0) base.resize(base.size() - 5);
  return base.empty() ? p.source : base;
}

Json HeaderJson(
    const std::string& tool, const std::string& command, const Problem& p, const std::string& file, bool with_model) {
  Json j{{"schema_version", kSchemaVersion},
         {"tool", tool},
         {"version", PLATEBALL_VERSION_STRING},
         {"command", command},
         {"problem", Json{{"name", ProblemName(p)}, {"file", file.empty() ? Json(nullptr) : Json(file)}}}};
  if (with_model) j["model"] = ToJson(p.model);
  j["integration"] = Json{{"absolute_tolerance", p.integration.absolute_tolerance},
                          {"relative_tolerance", p.integration.relative_tolerance},
                          {"max_steps", p.integration.max_steps}};
  j["seed"] = p.seed;
  return j;
}

Json InitialJson(const Problem& p) { return Json{{"angles", ToJson(p.initial)}, {"mu", p.mu}, {"x0", ToJson(p.x0)}}; }

Json ResultJson(const std::string& status, bool usable, const std::string& message, const std::string& report) {
  return Json{{"status", status}, {"usable", usable}, {"message", message}, {"report", report}};
}

void Append(Json& doc, Json part) {
  for (auto it = part.begin(); it != part.end(); ++it) doc[it.key()] = std::move(it.value());
}

namespace {
// Our documents are shallow (a few levels), so plain recursion is fine here.
void CheckFinite(const Json& j, const std::string& path) {
  if (j.is_number_float() && !std::isfinite(j.get<double>()))
    throw std::logic_error("output value " + (path.empty() ? std::string("(document)") : path) + " = " +
                           std::to_string(j.get<double>()) + " is not finite");
  if (j.is_object())
    for (auto it = j.begin(); it != j.end(); ++it)
      CheckFinite(it.value(), path.empty() ? it.key() : path + "." + it.key());
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i) CheckFinite(j[i], path + "[" + std::to_string(i) + "]");
}

// The scan of every output (a plan of n = 64 has ~10^4 numbers) without building a path per node;
// CheckFinite then names the first offending one.
bool AllFinite(const Json& j) {
  if (j.is_number_float()) return std::isfinite(j.get<double>());
  if (j.is_object() || j.is_array())
    for (const Json& e : j)
      if (!AllFinite(e)) return false;
  return true;
}

bool IsScalar(const Json& j) { return !j.is_object() && !j.is_array(); }
bool IsScalarArray(const Json& j) {
  if (!j.is_array()) return false;
  for (const Json& e : j)
    if (!IsScalar(e)) return false;
  return true;
}
std::string Scalar(const Json& j) { return j.dump(-1, ' ', false, Json::error_handler_t::replace); }
std::string InlineArray(const Json& j) {  // [a, b] or [[a, b], [c, d]]
  std::string s = "[";
  bool first = true;
  for (const Json& e : j) {
    s += first ? "" : ", ";
    first = false;
    s += e.is_array() ? InlineArray(e) : Scalar(e);
  }
  return s + "]";
}

// Objects one key per line; vectors, matrices and short point lists on one line each, so that a
// sample reads as a few lines rather than dozens.
void Write(const Json& j, int indent, std::string* out) {
  const std::string pad(static_cast<std::size_t>(indent + 2), ' ');
  const std::string close_pad(static_cast<std::size_t>(indent), ' ');
  if (j.is_object()) {
    if (j.empty()) {
      *out += "{}";
      return;
    }
    *out += "{\n";
    bool first = true;
    for (auto it = j.begin(); it != j.end(); ++it) {
      *out += first ? "" : ",\n";
      first = false;
      *out += pad + Scalar(Json(it.key())) + ": ";
      Write(it.value(), indent + 2, out);
    }
    *out += "\n" + close_pad + "}";
  } else if (j.is_array()) {
    bool nested_scalar_arrays = true;
    for (const Json& e : j) nested_scalar_arrays = nested_scalar_arrays && IsScalarArray(e);
    if (j.empty() || IsScalarArray(j)) {
      *out += InlineArray(j);
    } else if (nested_scalar_arrays && j.size() <= 3) {  // a matrix or a short list of points
      *out += InlineArray(j);
    } else {
      *out += "[\n";
      for (std::size_t i = 0; i < j.size(); ++i) {
        *out += (i ? ",\n" : "") + pad;
        Write(j[i], indent + 2, out);
      }
      *out += "\n" + close_pad + "]";
    }
  } else {
    *out += Scalar(j);
  }
}

}  // namespace

std::string DumpJson(const Json& doc) {
  if (!AllFinite(doc)) CheckFinite(doc, "");
  std::string out;
  Write(doc, 0, &out);
  return out + "\n";
}

std::string DumpJsonAt(const Json& value, int indent) {
  CheckFinite(value, "");
  std::string out;
  Write(value, indent, &out);
  return out;
}

void WriteJson(const Json& doc, const std::string& out_path) { WriteOutput(out_path, DumpJson(doc)); }

}  // namespace plateball::tools
