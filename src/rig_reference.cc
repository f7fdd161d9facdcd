#include "plateball/rig_reference.h"

#include <algorithm>
#include <stdexcept>

#include "check.h"
#include "plateball/isoparallel_plan.h"
#include "rig_geometry.h"

namespace plateball {

namespace {

void AddOnce(std::vector<std::string>* names, const std::string& name) {
  if (std::find(names->begin(), names->end(), name) == names->end()) names->push_back(name);
}

void CheckPoint(const RigLimits& l,
                const Eigen::Vector2d& x0,
                const Eigen::Vector2d& x,
                std::vector<std::string>* out) {
  internal::VisitGeometricMargins(l, x0, x, [out](const std::string& name, double margin) {
    if (margin < 0) AddOnce(out, name);
  });
}

}  // namespace

std::vector<std::string> PathLimitBreaks(const Path& path,
                                         const RigLimits& limits,
                                         const Eigen::Vector2d& x0,
                                         int samples_per_piece) {
  if (samples_per_piece < 1 || samples_per_piece > 1'000'000)
    internal::ThrowInvalid("samples_per_piece", samples_per_piece, "must be in [1, 1000000]");
  std::vector<std::string> out;
  for (const SmoothCurve& c : path.pieces())
    for (int i = 0; i <= samples_per_piece; ++i)
      CheckPoint(limits, x0, c.Value(c.Begin() + (c.End() - c.Begin()) * i / samples_per_piece), &out);
  return out;
}

ReferenceChoice ChooseIsoparallelReference(const IsoparallelSummary& summary,
                                           const RigLimits& limits,
                                           const Eigen::Vector2d& x0) {
  if (summary.solutions.empty()) internal::ThrowInvalid("summary.solutions", "(empty)", "holds no solution to choose");
  ReferenceChoice choice;
  for (std::size_t k = 0; k < summary.solutions.size(); ++k) {
    const std::vector<std::string> breaks = PathLimitBreaks(OptimalPath(summary.solutions[k]), limits, x0);
    if (k == 0) choice.shortest_breaks = choice.chosen_breaks = breaks;
    if (breaks.empty()) {
      choice.index = k;
      choice.chosen_breaks.clear();
      return choice;
    }
  }
  return choice;
}

}  // namespace plateball
