// `plateball view`: what the 3-D page shows, built from a tool's result JSON (plan,
// simulate, isoparallel, steer) by re-simulating the motion with the library: dense samples of
// the contact point x(t) and the orientation A(t) (FreeMotion, arc by arc from the result's
// impulses), the planned path, a ghost ball rolling along it, the impulses and the orientation
// error between the ball and the ghost.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/json_output.h"
#include "plateball/rig_limits.h"

namespace plateball::tools::view {

/// The one mapping from the concepts the view reads to the result JSON's field paths (dotted,
/// relative to the object they are read from; several paths: the first one present), loaded
/// from web/result_fields.json (embedded at build time): a renamed output field is a one-line
/// change there.
class ResultFields {
 public:
  explicit ResultFields(const nlohmann::json& mapping);
  /// The dotted paths of `concept_name`; throws std::logic_error for a concept the mapping lacks.
  const nlohmann::json& Paths(const std::string& concept_name) const;

 private:
  nlohmann::json mapping_;
};

/// Reads fields of one result document, naming the file and the field path in every error
/// (std::invalid_argument, exit code 3).
class ResultReader {
 public:
  ResultReader(std::string file, const nlohmann::json& doc, const ResultFields& fields);
  const nlohmann::json& doc() const { return doc_; }
  const ResultFields& fields() const { return fields_; }
  const std::string& file() const { return file_; }
  /// The value at concept's path below `at` (`where` names `at` in messages), or nullptr.
  const nlohmann::json* Find(const nlohmann::json& at, const std::string& concept_name) const;
  const nlohmann::json& Get(const nlohmann::json& at, const std::string& where, const std::string& concept_name) const;
  double Number(const nlohmann::json& at, const std::string& where, const std::string& concept_name) const;
  Eigen::Vector2d Vector2(const nlohmann::json& at, const std::string& where, const std::string& concept_name) const;
  Eigen::Vector3d Vector3(const nlohmann::json& at, const std::string& where, const std::string& concept_name) const;
  /// A rotation matrix (rows), checked to 1e-9.
  Eigen::Matrix3d Rotation(const nlohmann::json& at, const std::string& where, const std::string& concept_name) const;
  /// An array with at least `min_size` and at most `max_size` elements.
  const nlohmann::json& Array(const nlohmann::json& at,
                              const std::string& where,
                              const std::string& concept_name,
                              std::size_t min_size,
                              std::size_t max_size) const;
  [[noreturn]] void Fail(const std::string& field, const std::string& value, const std::string& what) const;

 private:
  std::string file_;
  const nlohmann::json& doc_;
  const ResultFields& fields_;
};

/// A JSON value as text for a message: compact, cut to kMaxValueTextChars characters.
std::string ValueText(const nlohmann::json& j);

struct ViewImpulse {
  double t = 0.0;
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  Eigen::Vector3d plate_velocity_change = Eigen::Vector3d::Zero();
};

/// A steer result's rig (rig_limits.h): the problem's limits, drawn on the plates, and the verdict of
/// the result's independent replay check (CheckRigLimits), shown in the info panel.
struct ViewRig {
  RigLimits limits;  ///< from the problem file, lengths in ball radii
  /// x0, where the stroke is measured from: the upper plate's reference point (the point above
  /// the contact point's start) stays in x0 + [-s_x, s_x] x [-s_y, s_y].
  Eigen::Vector2d stroke_origin = Eigen::Vector2d::Zero();
  bool checked = false;  ///< the result carries the rig object (the fields below)
  bool passed = false;
  long long samples = 0;  ///< contact points the replay checked
  bool constrained = false;
  std::string objective;
  std::vector<std::pair<std::string, double>> margins;  ///< limit, smallest bound - value
  std::vector<std::string> violations, active, blocking;
};

/// Everything the page draws; times are the motion's own (normalised units).
struct ViewData {
  std::string kind;                                        ///< "simulate", "plan", "isoparallel", "steer", "montecarlo"
  std::string title;                                       ///< problem name and command
  std::vector<std::pair<std::string, std::string>> facts;  ///< label, value (the info panel)
  std::vector<double> t;
  std::vector<Eigen::Vector2d> x;
  std::vector<Eigen::Matrix3d> A;        ///< the library's A(t) at t[i]
  std::vector<Eigen::Vector2d> ghost_x;  ///< empty without a planned path
  std::vector<Eigen::Matrix3d> ghost_A;
  std::vector<Eigen::Vector2d> planned;  ///< the planned path, dense polyline
  std::vector<ViewImpulse> impulses;
  /// Monte Carlo: the final contact points of the trials re-run, per (scenario, strategy) cell.
  std::vector<std::pair<std::string, std::vector<Eigen::Vector2d>>> spread;
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();
  bool has_goal = false;
  /// Largest |A - A_result| (max entry) where the re-simulation meets an orientation the result
  /// reports (arc ends, samples): how well the view reproduces the file.
  double resimulation_mismatch = 0.0;
  std::optional<ViewRig> rig;  ///< a steer result whose problem has a rig section
};

/// Options of the view: a problem file for results whose planned path is not in the JSON
/// (plan, steer); empty: the header's problem.file.
struct ViewOptions {
  std::string problem_file;
  int samples = 4000;  ///< target number of samples of the ball's motion (at least)
};

/// A result document's text as JSON (nested at most limits::kMaxJsonDepth deep); throws
/// std::invalid_argument naming `file` for malformed JSON.
nlohmann::json ParseResult(const std::string& file, const std::string& text);

/// Builds the view of a result document; throws std::invalid_argument naming the file and field.
ViewData BuildView(const ResultReader& reader, const ViewOptions& options);

/// The page draws in single precision (WebGL): a float resolves a position to 1/16 ball radius up
/// to 10^6, and the grid of the plate is scaled to at most 200 lines. Motions reaching farther are
/// refused rather than drawn as jitter (or not at all, once coordinates overflow a float).
inline constexpr double kMaxDrawnCoordinate = 1e6;
/// Refuses (std::invalid_argument naming `file` and the point) a view with a point the page cannot
/// draw: a coordinate beyond kMaxDrawnCoordinate ball radii, or not finite.
void CheckDrawable(const std::string& file, const ViewData& data);

/// The page data as JSON (the page's own format, see web/view.js).
nlohmann::json ViewDataToJson(const ViewData& data);

}  // namespace plateball::tools::view
