# Table-driven bad-input cases of isoparallel_solve (exact exit codes, the field named,
# bounded time, no NaN) and byte-identical plan files across runs and solver thread counts.
if(TARGET isoparallel_solve)
  add_test(NAME Hardening.IsoparallelSolveBadInputAndReproducibility
    COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/isoparallel_bad_input.sh $<TARGET_FILE:isoparallel_solve>
            ${CMAKE_CURRENT_BINARY_DIR}/isoparallel_bad_input)
  set_tests_properties(Hardening.IsoparallelSolveBadInputAndReproducibility PROPERTIES
    PASS_REGULAR_EXPRESSION "32 passed, 0 failed" TIMEOUT 900)
endif()
