# Tool side: hostile command-line cases of `plateball` and `isoparallel_solve` (exact exit
# codes, the option or file named, 10 s per case), atomic output files, "-" as standard output,
# escaped SVG, seeds as unsigned 64-bit integers.
if(TARGET plateball_cli AND TARGET isoparallel_solve)
  add_test(NAME Hardening.HostileCommandLines
    COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/hostile_cli.sh $<TARGET_FILE:plateball_cli>
            $<TARGET_FILE:isoparallel_solve> ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/hostile_cli)
  set_tests_properties(Hardening.HostileCommandLines PROPERTIES
    PASS_REGULAR_EXPRESSION "36 passed, 0 failed" TIMEOUT 600 LABELS cli)
endif()
