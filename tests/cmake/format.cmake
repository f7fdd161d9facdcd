# Every tracked C and C++ file is as clang-format leaves it under .clang-format (tests/scripts/check_format.sh).
# Registered where clang-format is installed (scripts/setup.sh installs it with the test tools) and the source
# is a git checkout.
find_program(PLATEBALL_CLANG_FORMAT NAMES clang-format clang-format-14)
if(PLATEBALL_CLANG_FORMAT AND EXISTS ${PROJECT_SOURCE_DIR}/.git)
  add_test(NAME Hygiene.Format
    COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/check_format.sh ${PROJECT_SOURCE_DIR} ${PLATEBALL_CLANG_FORMAT})
  set_tests_properties(Hygiene.Format PROPERTIES PASS_REGULAR_EXPRESSION "files formatted" TIMEOUT 120)
endif()
