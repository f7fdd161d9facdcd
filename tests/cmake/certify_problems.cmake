# scripts/certify_problems.py (reruns the certificates problem files claim) on a one-second
# lower-bound certificate: its exit codes and report (tests/scripts/check_certify_problems.py).
if(TARGET isoparallel_solve)
  add_test(NAME Scripts.CertifyProblemsReportsAndChecksCertificates
           COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/scripts/check_certify_problems.py
                   $<TARGET_FILE:isoparallel_solve>)
  set_tests_properties(Scripts.CertifyProblemsReportsAndChecksCertificates PROPERTIES LABELS "cli")
endif()
