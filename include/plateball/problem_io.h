// The one reader and writer of plateball's JSON problem files (schema: README.md, "Problem
// files"). Every error is a std::invalid_argument whose message reads
//   "FILE: FIELD.PATH: value VALUE: what is wrong"
// e.g. "figure7.json: initial.mu: value -1: must be > 0". The reader never crashes: any byte
// string either parses to a valid Problem or throws std::invalid_argument.
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>

#include "plateball/export.h"
#include "plateball/problem.h"

namespace plateball PLATEBALL_EXPORT {

/// Thrown by ReadProblemFile when the file cannot be opened or read. It is an invalid_argument
/// like every other reader error; command-line tools catch it first to report an I/O failure.
class ProblemFileReadError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Reads and validates the problem file at `path` (messages name the file as given in `path`).
/// Throws ProblemFileReadError when the file cannot be read, std::invalid_argument otherwise.
Problem ReadProblemFile(const std::string& path);

/// Parses and validates a problem from JSON text; `source_name` names it in messages and is
/// stored in Problem::source.
Problem ParseProblem(const std::string& json_text, const std::string& source_name = "<memory>");

/// Canonical JSON of a problem: fixed key order, two-space indentation, every default written
/// out, orientations as rotation matrices, numbers in shortest round-trip form. Deterministic,
/// and ParseProblem(WriteProblemJson(p)) == p field by field (bit-exact numbers). Throws
/// std::invalid_argument naming the field when p holds a non-finite number.
std::string WriteProblemJson(const Problem& p);

/// Parses an orientation given in any of the three file forms, as JSON text:
/// {"quaternion": [w, x, y, z]}, {"matrix": [[...], [...], [...]]} or
/// {"axis_angle": {"axis": [x, y, z], "angle": a}}. `field` names it in messages. Used by tools
/// that take an orientation on the command line.
Eigen::Matrix3d ParseOrientation(const std::string& json_text,
                                 const std::string& field,
                                 const std::string& source_name = "<command line>");

}  // namespace PLATEBALL_EXPORT
