# The C API as an external consumer sees it: examples/c/controller_loop.c compiled by the C compiler
# (C99, -Werror) in a CMake project of its own, configured in a temporary directory against the
# build tree's include directory and shared library (tests/c_consumer/run_c_consumer.cmake).
add_test(NAME c_api.consumer_builds_and_runs_the_c_example
         COMMAND ${CMAKE_COMMAND}
                 -DPLATEBALL_INCLUDE_DIR=${PROJECT_SOURCE_DIR}/include
                 -DPLATEBALL_LIBRARY=$<TARGET_FILE:plateball>
                 -DEXAMPLE_SOURCE=${PROJECT_SOURCE_DIR}/examples/c/controller_loop.c
                 -DCONSUMER_SOURCE=${PROJECT_SOURCE_DIR}/tests/c_consumer
                 -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/c_consumer
                 -DGENERATOR=${CMAKE_GENERATOR}
                 -DPROBLEM=${PROJECT_SOURCE_DIR}/problems/circle.json
                 -DSANITIZE=${PLATEBALL_SANITIZE}
                 -P ${PROJECT_SOURCE_DIR}/tests/c_consumer/run_c_consumer.cmake)
set_tests_properties(c_api.consumer_builds_and_runs_the_c_example PROPERTIES
  TIMEOUT 300 PASS_REGULAR_EXPRESSION "C consumer: ok")
