// The reading side of `plateball view`: the mapping from the view's concepts to the result's
// field paths (ResultFields), the checked reads of one result document that name the file and
// the field in every error (ResultReader), the parse of the result text with its nesting limit
// (ParseResult), and the check that the built data stays within what the page can draw
// (CheckDrawable). Building the drawable data from a result is in view_data.cc.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <variant>

#include "common/invalid_input.h"
#include "common/limits.h"
#include "common/number_format.h"
#include "plateball/so3.h"
#include "view/view_data.h"

namespace plateball::tools::view {

using nlohmann::json;

ResultFields::ResultFields(const json& mapping) : mapping_(mapping) {}

const json& ResultFields::Paths(const std::string& concept_name) const {
  const auto it = mapping_.find(concept_name);
  if (it == mapping_.end() || !it->is_array()) throw std::logic_error("result_fields.json lacks " + concept_name);
  return *it;
}

ResultReader::ResultReader(std::string file, const json& doc, const ResultFields& fields)
    : file_(std::move(file)), doc_(doc), fields_(fields) {}

std::string ValueText(const json& j) {
  std::string text = j.dump(-1, ' ', false, json::error_handler_t::replace);
  return text.size() > kMaxValueTextChars ? text.substr(0, kMaxValueTextChars) + "..." : text;
}

namespace {

const json* Walk(const json& at, const std::string& path) {
  const json* node = &at;
  std::size_t begin = 0;
  while (begin <= path.size() && !path.empty()) {
    const std::size_t end = std::min(path.find('.', begin), path.size());
    if (!node->is_object()) return nullptr;
    const auto it = node->find(path.substr(begin, end - begin));
    if (it == node->end()) return nullptr;
    node = &*it;
    begin = end + 1;
  }
  return node;
}

std::string Join(const std::string& where, const std::string& field) {
  return where.empty() ? field : where + "." + field;
}

}  // namespace

const json* ResultReader::Find(const json& at, const std::string& concept_name) const {
  for (const json& path : fields_.Paths(concept_name))
    if (const json* found = Walk(at, path.get<std::string>())) return found;
  return nullptr;
}

void ResultReader::Fail(const std::string& field, const std::string& value, const std::string& what) const {
  ThrowInvalidInput(file_ + ": " + field, value, what);
}

const json& ResultReader::Get(const json& at, const std::string& where, const std::string& concept_name) const {
  if (const json* found = Find(at, concept_name)) return *found;
  Fail(Join(where, fields_.Paths(concept_name).front().get<std::string>()), "(missing)", "required field is missing");
}

double ResultReader::Number(const json& at, const std::string& where, const std::string& concept_name) const {
  const json& j = Get(at, where, concept_name);
  if (!j.is_number() || !std::isfinite(j.get<double>()))
    Fail(Join(where, fields_.Paths(concept_name).front().get<std::string>()), ValueText(j), "must be a finite number");
  return j.get<double>();
}

namespace {
template <int N>
Eigen::Matrix<double, N, 1> VectorFrom(const ResultReader& r, const json& j, const std::string& field) {
  Eigen::Matrix<double, N, 1> v;
  if (!j.is_array() || j.size() != N)
    r.Fail(field, ValueText(j), "must be an array of " + std::to_string(N) + " numbers");
  for (int i = 0; i < N; ++i) {
    if (!j[i].is_number() || !std::isfinite(j[i].get<double>()))
      r.Fail(field, ValueText(j), "must be an array of " + std::to_string(N) + " finite numbers");
    v(i) = j[i].get<double>();
  }
  return v;
}
}  // namespace

Eigen::Vector2d ResultReader::Vector2(const json& at, const std::string& where, const std::string& concept_name) const {
  return VectorFrom<2>(*this, Get(at, where, concept_name), Join(where, fields_.Paths(concept_name).front()));
}

Eigen::Vector3d ResultReader::Vector3(const json& at, const std::string& where, const std::string& concept_name) const {
  return VectorFrom<3>(*this, Get(at, where, concept_name), Join(where, fields_.Paths(concept_name).front()));
}

Eigen::Matrix3d ResultReader::Rotation(const json& at,
                                       const std::string& where,
                                       const std::string& concept_name) const {
  const json& j = Get(at, where, concept_name);
  const std::string field = Join(where, fields_.Paths(concept_name).front());
  Eigen::Matrix3d m;
  if (!j.is_array() || j.size() != 3) Fail(field, ValueText(j), "must be a 3x3 matrix (rows)");
  for (int i = 0; i < 3; ++i) m.row(i) = VectorFrom<3>(*this, j[i], field).transpose();
  if (!IsRotation(m, 1e-9)) Fail(field, ValueText(j), "not a rotation matrix to 1e-9");
  return m;
}

const json& ResultReader::Array(const json& at,
                                const std::string& where,
                                const std::string& concept_name,
                                std::size_t min_size,
                                std::size_t max_size) const {
  const json& j = Get(at, where, concept_name);
  if (!j.is_array() || j.size() < min_size || j.size() > max_size)
    Fail(Join(where, fields_.Paths(concept_name).front()),
         j.is_array() ? "[array of " + std::to_string(j.size()) + "]" : ValueText(j),
         "must be an array of " + std::to_string(min_size) + " ... " + std::to_string(max_size) + " elements");
  return j;
}

json ParseResult(const std::string& file, const std::string& text) {
  const json::parser_callback_t depth_limit = [&](int depth, json::parse_event_t, json&) {
    if (depth > kMaxJsonDepth)
      ThrowInvalidInput(file + ": (document)",
                        "(nested deeper than " + std::to_string(kMaxJsonDepth) + ")",
                        "arrays and objects may be nested at most that deep");
    return true;
  };
  try {
    return json::parse(text, depth_limit);
  } catch (const json::exception& e) {
    throw std::invalid_argument(file + ": (document): value (see message): malformed JSON: " + e.what());
  }
}

void CheckDrawable(const std::string& file, const ViewData& d) {
  const auto check =
      [&](const char* what, const std::vector<Eigen::Vector2d>& points, const char* advice = "shorten the motion") {
        for (std::size_t i = 0; i < points.size(); ++i) {
          const double r = points[i].cwiseAbs().maxCoeff();
          if (!(r <= kMaxDrawnCoordinate))
            ThrowInvalidInput(file + ": " + what + "[" + std::to_string(i) + "]",
                              FormatNumber(r),
                              std::string("the page draws coordinates up to 1e6 ball radii; ") + advice);
        }
      };
  check("contact path (re-simulated)", d.x);
  check("planned path", d.planned);
  for (const auto& [label, points] : d.spread) check(("Monte Carlo final points of " + label).c_str(), points);
  if (d.has_goal) check("goal", {d.goal});
  if (d.rig) {  // the farthest points of the rig's shapes and of the stroke box
    const RigLimits& l = d.rig->limits;
    std::vector<Eigen::Vector2d> far;
    const auto add = [&](const PlateShape& shape) {
      if (const auto* disk = std::get_if<DiskShape>(&shape))
        far.push_back(disk->center.cwiseAbs() + Eigen::Vector2d::Constant(disk->radius + l.clearance));
      else
        for (const Eigen::Vector2d& v : std::get<PolygonShape>(shape).vertices)
          far.push_back(v.cwiseAbs() + Eigen::Vector2d::Constant(l.clearance));
    };
    if (l.plate) add(*l.plate);
    for (const PlateShape& o : l.obstacles) add(o);
    if (l.stroke) far.push_back(d.rig->stroke_origin.cwiseAbs() + *l.stroke);
    check("rig shape (plate, obstacles, stroke box)", far, "the rig reaches farther");
  }
}

}  // namespace plateball::tools::view
