# Command-line tests of `plateball steer` (issue 11, exact arrival): exit codes, messages, and the
# arrival errors of the certified problem files (the library tests re-integrate independently).
# Uses plateball_cli_test() from cli_tests.cmake (included before this file).
if(NOT TARGET plateball_cli OR NOT COMMAND plateball_cli_test)
  return()
endif()

plateball_cli_test(steer.help 0 REGEX "--impulses.*--svg" -- steer --help)
# Figure 7 goal with 12 impulses along the shortest isoparallel path: arrives; the paper's plan
# ends 0.3 rad off.
plateball_cli_test(steer.figure7_exact 0
  --number position_error 0 1e-12 --number orientation_error 0 1e-10 --number impulse_count 12 0
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

# isoparallel_solve --exact: the built-in Figure 7 problem arrives exactly with its 12 impulses.
if(TARGET isoparallel_solve)
  add_test(NAME IsoparallelCli.ExactArrivesWith12Impulses COMMAND isoparallel_solve --exact)
  set_tests_properties(IsoparallelCli.ExactArrivesWith12Impulses PROPERTIES
    PASS_REGULAR_EXPRESSION "exact arrival: arrived with 12 impulses, re-integrated errors: position [0-9.]+e-1[3-9], orientation [0-9.]+e-1[1-9] rad")
  add_test(NAME IsoparallelCli.ExactNeedsThreeImpulses COMMAND isoparallel_solve --exact --impulses 2)
  set_tests_properties(IsoparallelCli.ExactNeedsThreeImpulses PROPERTIES
    PASS_REGULAR_EXPRESSION "--impulses: value 2: must be in \\[3")
endif()
