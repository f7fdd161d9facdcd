# No tracker numbers ("issue N" with a number) in code, build files, help texts, problem files,
# schemas or the documentation outside its history appendix (tests/scripts/check_no_tracker_refs.sh).
add_test(NAME Hygiene.NoTrackerReferences
  COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/check_no_tracker_refs.sh ${PROJECT_SOURCE_DIR})
set_tests_properties(Hygiene.NoTrackerReferences PROPERTIES PASS_REGULAR_EXPRESSION "no tracker references" TIMEOUT 60)
