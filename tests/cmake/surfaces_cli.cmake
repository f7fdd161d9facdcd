# Bad input at the tools' surfaces (tests/scripts/surfaces_cli.sh): infinite physical energies,
# the problem-file size limit on standard input, FIFOs as input files, control characters in
# names, messages that name the file's field.
if(TARGET plateball_cli AND TARGET isoparallel_solve)
  add_test(NAME Hardening.Surfaces
    COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/surfaces_cli.sh $<TARGET_FILE:plateball_cli>
            $<TARGET_FILE:isoparallel_solve> ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/surfaces_cli)
  set_tests_properties(Hardening.Surfaces PROPERTIES
    PASS_REGULAR_EXPRESSION " passed, 0 failed" FAIL_REGULAR_EXPRESSION "FAIL:" TIMEOUT 300 LABELS cli)
endif()
