# The certificate's wing keeps its walls: no include cycle inside src/certify/, the vocabulary at
# the bottom, and no file of the library, tools or bindings outside it including its headers
# (tests/scripts/check_certify_layout.py).
add_test(NAME Layout.CertifyWing
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/scripts/check_certify_layout.py ${PROJECT_SOURCE_DIR})
set_tests_properties(Layout.CertifyWing PROPERTIES PASS_REGULAR_EXPRESSION "no include cycle, one public face"
                     TIMEOUT 60)
