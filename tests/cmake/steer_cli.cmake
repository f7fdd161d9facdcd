# Command-line tests of `plateball steer` (exact arrival): exit codes, messages, and the
# arrival errors of the certified problem files (the library tests re-integrate independently).
# Uses plateball_cli_test() from cli_tests.cmake (included before this file).
if(NOT TARGET plateball_cli OR NOT COMMAND plateball_cli_test)
  return()
endif()

plateball_cli_test(steer.help 0 REGEX "--impulses.*--svg" -- steer --help)
# Figure 7 goal with 12 impulses along the shortest isoparallel path: arrives; the paper's plan
# ends 0.3 rad off.
plateball_cli_test(steer.figure7_exact 0
  --at arrival.position_error 0 1e-12 --at replay.position_error 0 1e-12 --at arrival.orientation_error 0 1e-10
  --at replay.orientation_error 0 1e-10 --number impulse_count 12 0
  REGEX "\"status\": \"arrived\""
  -- steer problems/figure7_exact.json --summary-only)
plateball_cli_test(steer.figure7_exact_svg 0 REGEX "<svg.*stroke-dasharray"
  --cat ${CMAKE_CURRENT_BINARY_DIR}/cli_steer_figure7.svg
  -- steer problems/figure7_exact.json --summary-only --svg ${CMAKE_CURRENT_BINARY_DIR}/cli_steer_figure7.svg)
plateball_cli_test(steer.impulses_are_recorded 0 REGEX "\"x\": \\[.*\"p\": \\[.*\"plate_velocity_change\".*\"planned_delta_psi\""
  -- steer problems/figure7_exact.json --impulses 6)
plateball_cli_test(steer.too_few_impulses 3 REGEX "--impulses: value 2" -- steer problems/figure7_exact.json --impulses 2)
plateball_cli_test(steer.needs_a_steer_task 3 REGEX "steer" -- steer problems/circle.json)
plateball_cli_test(steer.missing_file 5 -- steer problems/no_such_problem.json)

# Fewest impulses (T5b): the certified files; every arrival's replay error is checked by --number.
plateball_cli_test(steer.figure7_fewest 0
  --number fewest_impulses 2 0 --at pareto[1].impulse_count 2 0 --at pareto[1].total_time 12.566370614359172 1e-9
  REGEX "\"status\": \"found\".*\"kind\": \"stop\""
  -- steer problems/figure7_fewest.json --max-impulses 2)
plateball_cli_test(steer.rotation_fewest_from_rest 0 --number fewest_impulses 3 0
  REGEX "\"kind\": \"start\".*\"mu_before\": 0"
  -- steer problems/isoparallel_rotation_fewest.json --max-impulses 3)
plateball_cli_test(steer.fewest_not_found 4 --number fewest_impulses 0 0 REGEX "\"status\": \"not_found\""
  -- steer problems/isoparallel_rotation_fewest.json --max-impulses 2 --starts 2 --summary-only)
plateball_cli_test(steer.fewest_bad_starts 3 REGEX "--starts: value 0" -- steer problems/figure7_exact.json --fewest-impulses --starts 0)
plateball_cli_test(steer.fewest_svg 0 REGEX "<svg.*stroke-dasharray.*straight line to the goal"
  --cat ${CMAKE_CURRENT_BINARY_DIR}/cli_steer_fewest.svg
  -- steer problems/figure7_fewest.json --max-impulses 2 --summary-only --svg ${CMAKE_CURRENT_BINARY_DIR}/cli_steer_fewest.svg)
plateball_cli_test(steer.stop_at_goal 0 REGEX "\"kind\": \"stop\",[ \n]*\"t_impulse\""
  -- steer problems/figure7_exact.json --stop-at-goal --impulses 6)

# isoparallel_solve --exact: the built-in Figure 7 problem arrives exactly with its 12 impulses.
if(TARGET isoparallel_solve)
  add_test(NAME IsoparallelCli.ExactArrivesWith12Impulses COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/check_cli.sh 0 -- $<TARGET_FILE:isoparallel_solve> --exact)
  set_tests_properties(IsoparallelCli.ExactArrivesWith12Impulses PROPERTIES
    FAIL_REGULAR_EXPRESSION "check_cli.sh: FAIL" PASS_REGULAR_EXPRESSION "exact arrival: arrived with 12 impulses, re-integrated errors: position [0-9.]+e-1[3-9], orientation [0-9.]+e-1[1-9] rad")
  add_test(NAME IsoparallelCli.ExactNeedsThreeImpulses
           COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/check_cli.sh 3 -- $<TARGET_FILE:isoparallel_solve> --exact --impulses 2)
  set_tests_properties(IsoparallelCli.ExactNeedsThreeImpulses PROPERTIES
    FAIL_REGULAR_EXPRESSION "check_cli.sh: FAIL" PASS_REGULAR_EXPRESSION "--impulses: value 2: --exact needs 3 ")
endif()
# mu only rescales time by 1/sqrt(mu): at mu = 1e12 and 1e-8 the same deviation as at mu = 1
# (0.2130914...), the total time 11.365464870055014 / sqrt(mu), arrived (exit 0).
plateball_cli_test(steer.exact_large_mu_is_time_scaled 0
  --at total_time 1.1365464870055014e-05 1e-18 REGEX "\"value\": 0.21309140"
  -- steer problems/figure7_exact.json --mu 1e12 --summary-only)
plateball_cli_test(steer.exact_small_mu_is_time_scaled 0
  --at total_time 113654.64870055014 1e-7 REGEX "\"value\": 0.21309140"
  -- steer problems/figure7_exact.json --mu 1e-8 --summary-only)
# The search's options without the search are an error naming both options.
plateball_cli_test(steer.max_impulses_needs_fewest 3 REGEX "--max-impulses: value 3: needs --fewest-impulses"
  -- steer problems/figure7_exact.json --max-impulses 3)
plateball_cli_test(steer.starts_needs_fewest 3 REGEX "--starts: value 5: needs --fewest-impulses"
  -- steer problems/figure7_exact.json --starts 5)
# The exact arrival's worst case is bounded (README, Limits): 200 impulses x 50 iterations.
plateball_cli_test(steer.impulses_beyond_the_limit 3 REGEX "--impulses: value 201: must be in \\[3, 200\\]"
  -- steer problems/figure7_exact.json --impulses 201 --summary-only)

# The fewest-impulse search's window is bounded up front (limits.h, kMaxFewestWindowLength): a goal
# too far away and a window set too long are input errors naming the file's field, not hours of work.
plateball_cli_test(steer.fewest_goal_too_far 3
  REGEX "steer.goal: value \\(400, 0\\): the goal is 400 radii from x0: the search window rolls .* more than the limit 500"
  -- steer tests/data/fewest_far_goal.json --summary-only)
plateball_cli_test(steer.fewest_window_too_long 3
  REGEX "steer.fewest.max_total_time: value 600: the search window rolls sqrt\\(mu\\) T = 600 radii, more than the limit 500"
  -- steer tests/data/fewest_long_window.json --summary-only)
# --progress reports the search (starts tried, elapsed time) on standard error.
plateball_cli_test(steer.fewest_progress 0 REGEX "fewest-impulse search, starts tried: done in"
  -- steer problems/figure7_fewest.json --max-impulses 2 --summary-only --progress)

# A rig: the Figure 7 goal on a disk plate that cuts the free optimum, with an obstacle on its
# path. The shortest isoparallel path breaks both, a longer solution meets them and is the reference;
# the arrival meets the limits and the independent replay check passes.
plateball_cli_test(steer.rig_figure7 0
  --at arrival.position_error 0 1e-12 --at replay.position_error 0 1e-12 --at arrival.orientation_error 0 1e-10
  --at replay.orientation_error 0 1e-10
  REGEX "\"solution_index\": [1-9].*\"shortest_breaks\": \\[\"obstacles\\[0\\]\", \"plate\"\\].*\"constrained\": true.*\"passed\": true"
  -- steer problems/figure7_rig.json --summary-only)
plateball_cli_test(steer.rig_svg 0 REGEX "<svg.*plate edge.*obstacles"
  --cat ${CMAKE_CURRENT_BINARY_DIR}/cli_steer_rig.svg
  -- steer problems/figure7_rig.json --summary-only --svg ${CMAKE_CURRENT_BINARY_DIR}/cli_steer_rig.svg)
plateball_cli_test(steer.rig_limits_not_met 4
  REGEX "\"status\": \"limits_not_met\".*\"blocking\": \\[[^]]*\"max_plate_velocity_change\""
  -- steer tests/data/rig_unreachable.json --summary-only)

# The fewest-impulse search on a rig: slack limits give the result without them, byte for byte
# (tests/scripts/fewest_slack_rig.py); limits that no arrival meets are the status limits_not_met
# naming them (the stop at the goal alone changes the plate's velocity by 2 |omega_h| > 0.05).
add_test(NAME cli.steer.fewest_slack_rig_identical
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/scripts/fewest_slack_rig.py
                 $<TARGET_FILE:plateball_cli> ${PROJECT_SOURCE_DIR})
set_tests_properties(cli.steer.fewest_slack_rig_identical PROPERTIES TIMEOUT 120 LABELS cli
                     PASS_REGULAR_EXPRESSION "fewest search: identical with slack rig limits")
plateball_cli_test(steer.fewest_rig_limits_not_met 4
  REGEX "\"status\": \"limits_not_met\".*blocked by [^\"]*max_plate_velocity_change"
  -- steer tests/data/fewest_rig_unreachable.json --max-impulses 2 --summary-only)
plateball_cli_test(steer.fewest_objective_impulse 3 REGEX "steer.objective: value \"impulse\": the fewest-impulse search ranks"
  -- steer tests/data/fewest_objective_impulse.json)
