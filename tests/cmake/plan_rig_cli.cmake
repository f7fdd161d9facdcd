# `plan` with a rig section: the plan checked against the limits by an independent replay of its
# flights (CheckPlanRigLimits; tests/plan_rig_check_test.cc checks the margins against a dense
# integration). The circle's pass points lie on the circle of radius 2 about (-2, 0), its flights bow
# inwards to 1.9952: a plate of radius 3 about the centre keeps a margin of 1 (at the pass points),
# an obstacle of radius 1.5 at the centre 0.4952, and one of radius 1.998 is entered by 0.0028.
plateball_cli_test(plan.rig_limits_met 0
  REGEX "rig limits met.*\"passed\": true.*\"obstacles\\[0\\]\": 0\\.495[0-9]*,"
  --at rig.check.margins.plate 1 1e-9 --at rig.check.margins.min_interval 0.2273 1e-3
  -- plan problems/plan_rig_circle.json --summary-only)
plateball_cli_test(plan.rig_obstacle_in_the_bow 4
  REGEX "\"status\": \"limits_not_met\".*obstacles\\[0\\] exceeded by [0-9.e-]+ at flight.*\"obstacles\\[0\\]\": -0\\.002[0-9]*,"
  -- plan tests/data/plan_rig_blocked.json --summary-only)
