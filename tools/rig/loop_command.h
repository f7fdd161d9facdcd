// `plateball rig loop PROBLEM.json`: the real-time controller in a closed loop with the MuJoCo twin
// as its plant (rig/twin_loop.h), beside the open loop in the twin and the library's own simulated
// closed loop for the same seed and errors; JSON with the per-impulse records and the final errors.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

#include "common/json_output.h"
#include "rig/mujoco_twin.h"

namespace plateball::tools {

/// The twin's integrator and contact settings: the `settings` object of every `rig` output.
Json TwinSettingsJson(const rig::TwinSettings& s);

/// Adds the options of `rig loop` to `sub`; the returned function runs it.
std::function<int()> SetupRigLoop(CLI::App& sub);

}  // namespace plateball::tools
