# `plan` with a rig section: the planner honours the limits (PlanImpulsesOnRig; tests/rig_planner_test.cc
# checks it against a denser check and a second integrator) and an independent replay of its flights
# checks them (CheckPlanRigLimits; tests/plan_rig_check_test.cc checks the margins against a dense
# integration). The circle's pass points lie on the circle of radius 2 about (-2, 0), its flights bow
# inwards to 1.9952 at 64 impulses: a plate of radius 3 about the centre keeps a margin of 1 (at the
# pass points), an obstacle of radius 1.5 at the centre 0.4952, and one of radius 1.998 is entered by
# 0.0028 unless the partition is refined (128 impulses bow to 1.9988).
if(NOT TARGET plateball_cli)
  return()
endif()
plateball_cli_test(plan.rig_limits_met 0
  REGEX "rig limits met.*\"points_added\": 0,.*\"passed\": true.*\"obstacles\\[0\\]\": 0\\.495[0-9]*,"
  --at rig.check.margins.plate 1 1e-9 --at rig.check.margins.min_interval 0.2273 1e-3
  -- plan problems/plan_rig_circle.json --summary-only)
plateball_cli_test(plan.rig_obstacle_in_the_bow_refined 0
  REGEX "rig limits met \\(active: obstacles\\[0\\]; 64 partition points added.*\"passed\": true.*\"obstacles\\[0\\]\": 0\\.0007[0-9]*,"
  --at partition.segments 128 0 --at rig.points_added 64 0
  -- plan tests/data/plan_rig_blocked.json --summary-only)
plateball_cli_test(plan.rig_obstacle_in_the_bow_check_only 4
  REGEX "\"status\": \"limits_not_met\".*obstacles\\[0\\] exceeded by [0-9.e-]+ at flight.*\"mode\": \"check\".*\"obstacles\\[0\\]\": -0\\.002[0-9]*,"
  -- plan tests/data/plan_rig_blocked.json --summary-only --rig-check-only)
# A 1 kHz loop: every interior partition point slides onto the grid (the check compares with ==).
plateball_cli_test(plan.rig_tick_slid 0
  REGEX "active: obstacles\\[0\\] tick; 64 partition points added, 127 slid onto the tick grid.*\"tick\": 0\\.0"
  --at rig.check.margins.tick 0 0 --at max_pass_miss 0 1e-11
  -- plan tests/data/plan_rig_tick.json --summary-only)
# The path itself crosses the obstacle: blocked, naming the obstacle and the path point.
plateball_cli_test(plan.rig_path_through_obstacle 4
  REGEX "limits_not_met: .*the path itself enters obstacles\\[0\\] by 0\\.2499[0-9]* at p\\(tau = 1\\.5707963267948966\\).*\"blocking\": \\[[^]]*\"obstacles\\[0\\]\""
  -- plan tests/data/plan_rig_path_blocked.json --summary-only)
# Slack limits change nothing: the same JSON as without the rig section, byte for byte.
add_test(NAME cli.plan.rig_slack_identical
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/scripts/plan_slack_rig.py $<TARGET_FILE:plateball_cli>
                 ${PROJECT_SOURCE_DIR})
set_tests_properties(cli.plan.rig_slack_identical PROPERTIES TIMEOUT 120 LABELS cli)
# Flights of about 0.257 under a shortest interval of 0.3: every other interior point is removed
# (coarsening; tests/rig_planner_test.cc checks the intervals from the replayed impulse times).
plateball_cli_test(plan.rig_short_flights_merged 0
  REGEX "rig limits met \\(active: min_interval; 0 partition points added, 32 removed, 0 slid onto the tick grid\\).*\"points_removed\": 32,.*\"passed\": true"
  --at partition.segments 32 0 --at rig.points_removed 32 0
  -- plan tests/data/plan_rig_short.json --summary-only)
