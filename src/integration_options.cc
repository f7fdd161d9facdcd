#include "plateball/integration_options.h"

#include <cmath>
#include <sstream>

namespace plateball {

std::string IntegrationOptions::Validate() const {
  // Fast path: no string stream when valid (called once per join in the planner's loop).
  if (std::isfinite(absolute_tolerance) && absolute_tolerance > 0 && absolute_tolerance < 1 &&
      std::isfinite(relative_tolerance) && relative_tolerance > 0 && relative_tolerance < 1 &&
      !(absolute_tolerance < 1e-15 && relative_tolerance < 1e-15) && max_steps >= 1)
    return {};
  std::ostringstream os;
  if (!(std::isfinite(absolute_tolerance) && absolute_tolerance > 0 && absolute_tolerance < 1))
    os << "integration option 'absolute_tolerance' = " << absolute_tolerance << " must be in (0, 1)";
  else if (!(std::isfinite(relative_tolerance) && relative_tolerance > 0 && relative_tolerance < 1))
    os << "integration option 'relative_tolerance' = " << relative_tolerance << " must be in (0, 1)";
  else if (absolute_tolerance < 1e-15 && relative_tolerance < 1e-15)
    os << "integration options 'absolute_tolerance' = " << absolute_tolerance
       << " and 'relative_tolerance' = " << relative_tolerance << " are below double precision";
  else if (max_steps < 1)
    os << "integration option 'max_steps' = " << max_steps << " must be >= 1";
  return os.str();
}

}  // namespace plateball
