# Command-line tests of `plateball join`, `plateball plan` and `plateball converge`: exact exit codes,
# messages, and numbers checked against independent values (closed forms, Corollary 3).
# Uses plateball_cli_test() from cli_tests.cmake (included before this file).
if(NOT TARGET plateball_cli OR NOT COMMAND plateball_cli_test)
  return()
endif()

plateball_cli_test(join.help 0 REGEX "--targets.*--max-iterations" -- join --help)
plateball_cli_test(plan.help 0 REGEX "--n.*--svg" -- plan --help)
plateball_cli_test(converge.help 0 REGEX "--n.*--format.*--svg" -- converge --help)

# lambda = 1 (homogeneous ball): x' is constant with |x'| = sqrt(mu) = 2, so the target (0.3, 0.4)
# at distance 0.5 is reached at t = 0.25 exactly, with delta omega along the new direction.
plateball_cli_test(join.homogeneous_ball_time_is_distance_over_speed 0
  --number t 0.25 1e-12 --number residual 0 1e-12
  -- join --lambda 1 --mu 4 --theta 1.1 --phi -0.3 --psi 2 --targets 0.3,0.4)
# T1's first target: reached (the library tests check the point by a second integration).
plateball_cli_test(join.t1_target 0 REGEX "\"status\": \"converged\""
  -- join --lambda 2 --theta 1.0471975511965976 --phi 0.4 --psi 0.1 --targets 0.05,0)
plateball_cli_test(join.target_equal_to_start_is_a_status 4 REGEX "target_equals_start"
  -- join --lambda 2 --targets 0,0)
plateball_cli_test(join.needs_targets 3 REGEX "--targets" -- join --lambda 2)
plateball_cli_test(join.bad_target 3 REGEX "--targets" -- join --lambda 2 --targets 1,nan)

# Circle (T2): path length 4 pi; every partition point passed to 1e-10.
plateball_cli_test(plan.circle 0
  --number length 12.566370614359172 1e-10 --number max_pass_miss 0 1e-10
  REGEX "\"status\": \"success\""
  -- plan problems/circle.json --summary-only)
plateball_cli_test(plan.circle_svg 0 REGEX "<svg.*stroke-dasharray.*<circle"
  --cat ${CMAKE_CURRENT_BINARY_DIR}/cli_plan_circle.svg
  -- plan problems/circle.json --n 16 --summary-only --svg ${CMAKE_CURRENT_BINARY_DIR}/cli_plan_circle.svg)
plateball_cli_test(plan.steps_are_recorded 0 REGEX "\"plate_velocity_change\".*\"orientation_impulsive\""
  -- plan problems/piecewise.json --n 2)
plateball_cli_test(plan.n_must_be_positive 3 REGEX "--impulses: value 0" -- plan problems/circle.json --n 0)
plateball_cli_test(plan.needs_a_plan_task 3 REGEX "plan" -- plan problems/simulate_example.json)
plateball_cli_test(plan.missing_file 5 -- plan problems/no_such_problem.json)

# Corollary 3: error ~ n^-2; the bound holds for every n.
plateball_cli_test(converge.circle_slope 0
  --number error_slope -2 0.2 REGEX "\"bound_holds\": true"
  -- converge problems/circle.json --n 16,32,64,128)
plateball_cli_test(converge.csv 0 REGEX "n,segments,measured_error"
  -- converge problems/ellipse.json --n 16,32 --format csv)
# Wall times only on request (--timings): without it the output is reproducible byte for byte.
plateball_cli_test(converge.csv_timings 0 REGEX "n,segments,plan_seconds,measured_error"
  -- converge problems/ellipse.json --n 16,32 --format csv --timings)
# A repeated n, an n for an explicit partition: input errors naming --n; one n: no slope.
plateball_cli_test(converge.repeated_n 3 REGEX "--impulses.*repeated"
  -- converge problems/circle.json --n 16,16,16)
plateball_cli_test(converge.one_n 0 REGEX "no slope" -- converge problems/circle.json --n 16)
plateball_cli_test(converge.svg 0 REGEX "fit: slope -[12]\\."
  --cat ${CMAKE_CURRENT_BINARY_DIR}/cli_converge_lemniscate.svg
  -- converge problems/lemniscate.json --n 16,32,64 --svg ${CMAKE_CURRENT_BINARY_DIR}/cli_converge_lemniscate.svg)
plateball_cli_test(converge.bad_format 3 REGEX "--format" -- converge problems/circle.json --format xml)
