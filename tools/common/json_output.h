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
#include "plateball/problem.h"

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
/// A state object (docs/output_contract.md): {"t", "angles", "z", "x", "orientation", "omega",
/// "energy"}; the angles are the canonical ones (theta in [0, pi]).
Json ToJson(const MotionSample& s);
/// A rotation R with its logarithm: {"matrix", "rotation_vector" (w, R = exp(hat w), |w| <= pi),
/// "angle" (|w|), "axis" (w/|w|, only when the angle is > 0)}.
Json RotationToJson(const Eigen::Matrix3d& r);

/// Version of the output contract (docs/output_contract.md) written as "schema_version" by every
/// JSON document of the tools; bumped when a name or a shape changes.
inline constexpr int kSchemaVersion = 1;

/// The name a document gives its problem: the file's "name", else the file name without ".json",
/// else the source ("(built-in defaults)").
std::string ProblemName(const Problem& p);

/// The header every output document starts with (docs/output_contract.md, section 1):
/// schema_version, tool, version, command, problem {name, file (null when none)}, model (unless
/// `with_model` is false), integration, seed.
Json HeaderJson(const std::string& tool,
                const std::string& command,
                const Problem& p,
                const std::string& file,
                bool with_model = true);

/// The initial state of a problem as a state object: {"angles", "mu", "x0"}.
Json InitialJson(const Problem& p);

/// The four fields of every solver result: {"status", "usable", "message", "report"}.
Json ResultJson(const std::string& status, bool usable, const std::string& message, const std::string& report);

/// Moves every key of `part` to the end of `doc`, in order.
void Append(Json& doc, Json part);

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
