# The limits of plateball/limits.h as the tools apply them: standard input's 16 MiB, simulate's
# samples on the command line and in a file, `view` of the largest simulation, and `view`'s
# refusal of montecarlo counts the tool cannot have written.
if(TARGET plateball_cli)
  add_test(NAME Limits.CommandLines
    COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/limits_cli.sh $<TARGET_FILE:plateball_cli>
            ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/limits_cli $<BOOL:${PLATEBALL_SANITIZE}>)
  set_tests_properties(Limits.CommandLines PROPERTIES
    PASS_REGULAR_EXPRESSION "passed, 0 failed" TIMEOUT 300 LABELS cli)
endif()
