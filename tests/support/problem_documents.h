// Problem documents shared by the problem-file tests (problem_io_test.cc, problem_io_errors_test.cc):
// a valid document with every section, and the smallest valid one.
#pragma once

#include <nlohmann/json.hpp>

namespace plateball::testing {

// A valid document with every section filled, the base of the round trip and error cases.
inline nlohmann::json FullDocument() {
  return nlohmann::json::parse(R"({
    "name": "full",
    "description": "every section",
    "seed": 42,
    "integration": {"absolute_tolerance": 1e-11, "relative_tolerance": 1e-10, "max_steps": 50000},
    "ball": {"physical": {"inertia_1": 0.4, "inertia_3": 0.3, "ball_mass": 1.0, "radius": 1.0, "plate_mass": 0.25}},
    "initial": {"theta": -1.0471975511965976, "phi": 1.5707963267948966, "psi": 0.1, "mu": 1.3,
                "x0": [0.5, -0.25], "orientation": {"quaternion": [0.9, 0.1, -0.3, 0.2]}},
    "simulate": {"t_end": 12.5, "samples": 7},
    "reach": {"targets": [[1, 2], [-3.5, 0.25]], "horizon_periods": 4},
    "plan": {
      "path": {"type": "piecewise", "pieces": [
        {"type": "line", "from": [0, 0], "to": [1, 0]},
        {"type": "circle", "center": [1, 1], "radius": 1, "tau_begin": -1.5707963267948966, "tau_end": 0},
        {"type": "samples", "points": [[2, 1], [2.5, 1.5], [3, 1.25]]},
        {"type": "sine", "from": [3, 1.25], "rotation": 0.3, "length": 2, "amplitude": 0.1, "wavelength": 1}
      ]},
      "partition": {"type": "explicit", "taus": [0, 0.5, 1.5, 2]},
      "energy_changes": [{"index": 1, "factor": 0.5}, {"index": 2, "factor": 2}],
      "converge_n": [4, 8, 16]
    },
    "isoparallel": {"start": [0, 0], "goal": [3, 3],
                    "start_orientation": {"axis_angle": {"axis": [1, 0, 0], "angle": 0.5}},
                    "goal_orientation": {"matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]},
                    "impulses": 24,
                    "solver": {"starts": 10, "length_cap_factor": 2.5, "max_iterations": 60,
                               "tolerance": 1e-10, "threads": 2}},
    "expected": {"length": {"value": 7.25, "tolerance": 1e-6}, "count": {"value": 3, "tolerance": 0}}
  })");
}

inline nlohmann::json MinimalDocument() {
  return nlohmann::json::parse(R"({"ball": {"lambda": 1.5}, "initial": {"theta": 1, "phi": 0, "psi": 0, "mu": 1}})");
}

}  // namespace plateball::testing
