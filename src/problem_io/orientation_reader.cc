// The three forms of an orientation in a problem file: a unit quaternion [w, x, y, z], a rotation
// matrix (checked to 1e-9) or an axis and an angle.
#include <Eigen/Geometry>
#include <cmath>

#include "kinematics.h"
#include "plateball/so3.h"
#include "problem_io/field_reader.h"

namespace plateball::internal::problem_io {
namespace {

constexpr double kRotationTolerance = 1e-9;  // a "matrix" orientation must be a rotation to this
constexpr double kDegenerateNorm = 1e-12;    // quaternion / axis norms below this are zero

}  // namespace

Eigen::Matrix3d FieldReader::Orientation(const json& j, const std::string& path) const {
  Object(j, path, {"quaternion", "matrix", "axis_angle"});
  if (j.size() != 1) Fail(path, j, "must have exactly one of the keys quaternion, matrix, axis_angle");
  if (const json* q = Find(j, "quaternion")) {
    const std::string p = Join(path, "quaternion");
    const Eigen::Vector4d wxyz = Vector<4>(*q, p);
    const double n = wxyz.norm();
    if (!(n > kDegenerateNorm) || !std::isfinite(n))
      Fail(p, *q, "must be a non-zero quaternion [w, x, y, z] (it is normalised)");
    return QuaternionToRotation(wxyz, p);
  }
  if (const json* m = Find(j, "matrix")) {
    const std::string p = Join(path, "matrix");
    if (!m->is_array() || m->size() != 3) Fail(p, *m, "must be an array of 3 rows of 3 numbers");
    Eigen::Matrix3d r;
    for (std::size_t i = 0; i < 3; ++i)
      r.row(static_cast<Eigen::Index>(i)) = Vector<3>((*m)[i], Index(p, i)).transpose();
    const double orth = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    const double det = r.determinant();
    if (!IsRotation(r, kRotationTolerance) || !(orth <= kRotationTolerance) ||
        !(std::abs(det - 1.0) <= kRotationTolerance)) {
      Fail(p,
           *m,
           "not a rotation matrix to 1e-9: max |R^T R - I| = " + NumberText(orth) + ", det R = " + NumberText(det) +
               (det < 0 ? " (a reflection)" : ""));
    }
    return r;
  }
  const json& aa = *Find(j, "axis_angle");
  const std::string p = Join(path, "axis_angle");
  Object(aa, p, {"axis", "angle"});
  const Eigen::Vector3d axis = Vector<3>(Require(aa, p, "axis"), Join(p, "axis"));
  const double angle = Number(Require(aa, p, "angle"), Join(p, "angle"));
  const double n = axis.norm();
  if (!(n > kDegenerateNorm) || !std::isfinite(n))
    Fail(Join(p, "axis"), aa["axis"], "must be a non-zero vector (it is normalised)");
  // Beyond kMaxAngleMagnitude the rotation has no significant digits left (and ExpSO3 gives NaN).
  if (std::abs(angle) > kMaxAngleMagnitude)
    Fail(Join(p, "angle"), aa["angle"], "an angle beyond 1e15 in magnitude has no significant digits left modulo 2 pi");
  return ExpSO3(axis / n * angle);
}

}  // namespace plateball::internal::problem_io
