// The isoparallel summary's text (BriefReport, FullReport) and the names of its enums.
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>

#include "plateball/isoparallel.h"

namespace plateball {

std::string ToString(IsoparallelMethod method) {
  switch (method) {
    case IsoparallelMethod::kShooting:
      return "shooting";
    case IsoparallelMethod::kFamilyEnumeration:
      return "family_enumeration";
  }
  return "unknown";
}

std::string ToString(IsoparallelStatus status) {
  switch (status) {
    case IsoparallelStatus::kNotRun:
      return "not_run";
    case IsoparallelStatus::kSolved:
      return "solved";
    case IsoparallelStatus::kNoSolution:
      return "no_solution";
    case IsoparallelStatus::kIntegrationFailure:
      return "integration_failure";
  }
  return "unknown";
}

const IsoparallelSolution& IsoparallelSummary::Shortest() const {
  if (solutions.empty())
    throw std::logic_error("IsoparallelSummary::Shortest: no solution (status " + ToString(status) + ")");
  return solutions.front();
}

std::string IsoparallelSummary::BriefReport() const {
  std::ostringstream os;
  os << "Isoparallel: " << ToString(status) << ", " << solutions.size() << " solution(s)";
  if (!solutions.empty()) {
    os << std::setprecision(10) << ", shortest length " << solutions.front().length << std::setprecision(3)
       << ", verified residual " << solutions.front().orientation_residual;
  }
  os << std::setprecision(4) << ", " << local_solves << " local solves, " << time_seconds << " s";
  return os.str();
}

std::string IsoparallelSummary::FullReport() const {
  std::ostringstream os;
  os << BriefReport() << "\n";
  os << "  start (" << problem.start.transpose() << "), goal (" << problem.goal.transpose() << "), method "
     << ToString(method);
  if (method == IsoparallelMethod::kShooting)
    os << ", starts " << options.starts
       << (seeded ? ", seed " + std::to_string(options.seed) : std::string(", deterministic (no seed)"));
  else
    os << ", periods searched " << periods_searched << (complete ? ", complete" : ", NOT certified complete");
  os << ", searched length " << searched_length << "\n";
  for (std::size_t i = 0; i < solutions.size(); ++i) {
    const IsoparallelSolution& s = solutions[i];
    os << std::setprecision(10) << "  #" << i + 1 << " length " << s.length << " " << ToString(s.parameters.regime)
       << " G " << s.G << " E " << s.energy << " periods " << s.periods << (s.family ? " family" : "")
       << std::setprecision(3) << " crossing " << s.crossing << " residual " << s.orientation_residual << " endpoint "
       << s.endpoint_error << " conjugate " << s.conjugate_time
       << (s.locally_optimal ? " locally optimal" : " NOT locally optimal") << "\n";
  }
  os << "  Maxwell pairs (equal length, same goal): " << maxwell_pairs.size() << "\n";
  return os.str();
}

}  // namespace plateball
