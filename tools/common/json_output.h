// JSON output of the command-line tools: conversions of library values, full-precision numbers,
// stdout or an --out file. Shared by every subcommand so that all outputs read alike.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/free_motion.h"

namespace plateball::tools {

/// Keys keep their insertion order, so a document reads in the order it is built.
using Json = nlohmann::ordered_json;

Json ToJson(const Eigen::Vector2d& v);                    ///< [x, y]
Json ToJson(const Eigen::Vector3d& v);                    ///< [x, y, z]
Json ToJson(const Eigen::Matrix3d& m);                    ///< rows: [[m00, m01, m02], ...]
Json ToJson(const std::vector<Eigen::Vector2d>& points);  ///< [[x, y], ...]
Json ToJson(const AngleState& a);                         ///< {"theta", "phi", "psi"}
/// {"lambda"} plus {"alpha", "beta"} when the model knows its inertia.
Json ToJson(const BallModel& m);
/// {"t", "theta", "phi", "psi", "z", "x", "orientation", "omega", "energy"}; the angles are the
/// canonical ones (theta in [0, pi]).
Json ToJson(const MotionSample& s);
/// A rotation R with its logarithm: {"matrix", "rotation_vector" (w, R = exp(hat w), |w| <= pi),
/// "angle" (|w|), "axis" (w/|w|, only when the angle is > 0)}.
Json RotationToJson(const Eigen::Matrix3d& r);

/// Two-space indented text ending in a newline; vectors, matrices and short point lists on one
/// line each (it is still plain JSON for any reader). Doubles are written in the shortest form that
/// reads back to the same double (at most max_digits10 = 17 significant digits), so no digit is
/// lost. Throws std::logic_error naming the JSON path of the first non-finite number: a tool never
/// prints NaN, infinity or a null in place of a number.
std::string DumpJson(const Json& doc);

/// DumpJson of a value nested `indent` spaces deep (its lines after the first indented to match),
/// without the final newline: a streamed document's elements (sample_table.h).
std::string DumpJsonAt(const Json& value, int indent);

/// Writes DumpJson(doc) to stdout when `out_path` is empty or "-", else to the file `out_path`
/// (replaced atomically, output_file.h). Throws IoError (exit code 5) when it cannot be written.
void WriteJson(const Json& doc, const std::string& out_path);

}  // namespace plateball::tools
