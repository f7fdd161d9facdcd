# Messages about bad values name the field and the value as the user wrote them (a problem file's field,
# a command-line option), not a variable of the code, for problem files, options and results read by
# `plateball view` (tests/scripts/field_messages_cli.sh).
if(TARGET plateball_cli)
  add_test(NAME Hardening.FieldMessages
    COMMAND bash ${PROJECT_SOURCE_DIR}/tests/scripts/field_messages_cli.sh $<TARGET_FILE:plateball_cli>
            ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/field_messages_cli)
  set_tests_properties(Hardening.FieldMessages PROPERTIES
    PASS_REGULAR_EXPRESSION "23 passed, 0 failed" FAIL_REGULAR_EXPRESSION "FAIL:" TIMEOUT 300 LABELS cli)
endif()
