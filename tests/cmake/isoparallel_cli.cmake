# Command-line tests of isoparallel_solve: exit codes, the built-in Figure 7 problem, byte-identical
# plan files for the same problem and seed, SVG output.
if(TARGET isoparallel_solve)
  # Through check_cli.sh: a pass expression alone would let ctest ignore the exit code.
  add_test(NAME IsoparallelCli.BuiltInFigure7Succeeds COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/check_cli.sh 0 -- $<TARGET_FILE:isoparallel_solve>)
  set_tests_properties(IsoparallelCli.BuiltInFigure7Succeeds PROPERTIES
    PASS_REGULAR_EXPRESSION "shortest length: 9\\.4127724" FAIL_REGULAR_EXPRESSION "check_cli.sh: FAIL")
  add_test(NAME IsoparallelCli.HelpExitsZero COMMAND isoparallel_solve --help)
  add_test(NAME IsoparallelCli.UnknownOptionIsUsageError COMMAND isoparallel_solve --no-such-option)
  set_tests_properties(IsoparallelCli.UnknownOptionIsUsageError PROPERTIES WILL_FAIL TRUE)
  # --certify: not needed at an identity target (the enumeration is complete); at 3 rad about e3
  # and 0.2 away no path shorter than 3 exists (rolling turns the ball by at most the length), so
  # the certificate up to 0.25 must close with no solution.
  add_test(NAME IsoparallelCli.CertifyIsNotNeededAtAnIdentityTarget
           COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/check_cli.sh 0 -- $<TARGET_FILE:isoparallel_solve> --certify)
  set_tests_properties(IsoparallelCli.CertifyIsNotNeededAtAnIdentityTarget PROPERTIES
    FAIL_REGULAR_EXPRESSION "check_cli.sh: FAIL" PASS_REGULAR_EXPRESSION "certificate: not needed \\(the family enumeration is complete")
  add_test(NAME IsoparallelCli.CertifyProvesALowerBound
    COMMAND ${CMAKE_COMMAND} -DTOOL=$<TARGET_FILE:isoparallel_solve> -DWORK=${CMAKE_CURRENT_BINARY_DIR}/isoparallel_cli
            -P ${PROJECT_SOURCE_DIR}/tests/cmake/isoparallel_cli_lower_bound.cmake.in)
  add_test(NAME IsoparallelCli.ExitCodes
    COMMAND ${CMAKE_COMMAND} -DTOOL=$<TARGET_FILE:isoparallel_solve> -DSRC=${PROJECT_SOURCE_DIR}
            -DWORK=${CMAKE_CURRENT_BINARY_DIR}/isoparallel_cli
            -P ${PROJECT_SOURCE_DIR}/tests/cmake/isoparallel_cli_check.cmake.in)
endif()
