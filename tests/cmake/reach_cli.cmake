# `plateball reach` end to end: the Figure 8 problem file is solved (exit 0) and the JSON lists the
# closed-form solution of target (0, 10) (delta_psi = pi, t = 10); an unreachable target within a
# short horizon exits with 4 (no solution) and reports the closest approach.
if(TARGET plateball_cli)
  add_test(NAME ReachCli.Figure8ProblemIsSolved
           COMMAND plateball_cli reach ${PROJECT_SOURCE_DIR}/problems/figure8_reach.json
                   --svg ${CMAKE_CURRENT_BINARY_DIR}/figure8_reach.svg)
  set_tests_properties(ReachCli.Figure8ProblemIsSolved PROPERTIES
    PASS_REGULAR_EXPRESSION "\"delta_psi\": 3\\.14159265358979[0-9]*,[^}]*\"t\": (10|10\\.0|9\\.99999999999[0-9]*|10\\.00000000000[0-9]*),")
  add_test(NAME ReachCli.ShortHorizonExitsWithNoSolution
           COMMAND sh -c "\"$1\" reach \"$2\" --targets 6,0 --horizon-periods 0.1; test $? -eq 4" sh
                   $<TARGET_FILE:plateball_cli> ${PROJECT_SOURCE_DIR}/problems/figure8_reach.json)
endif()
