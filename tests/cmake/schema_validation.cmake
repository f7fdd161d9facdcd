# The output contract (docs/output_contract.md): every problem file, every output of the tools on
# problems/*.json and every README example validated against schemas/ (draft 2020-12), and broken
# documents rejected, with Debian's /usr/bin/python3 and python3-jsonschema (scripts/setup.sh).
if(TARGET plateball_cli AND TARGET isoparallel_solve)
  add_test(NAME schemas.validate
           COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/scripts/validate_schemas.py
                   --plateball $<TARGET_FILE:plateball_cli> --isoparallel-solve $<TARGET_FILE:isoparallel_solve>
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(schemas.validate PROPERTIES TIMEOUT 300 LABELS "cli;schemas"
                       PASS_REGULAR_EXPRESSION "broken documents rejected: [1-9]"
                       FAIL_REGULAR_EXPRESSION "FAIL: ")  # the pass pattern alone hid every failure
endif()
