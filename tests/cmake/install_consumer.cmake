# The library is an installable CMake package. This test installs the build tree into a
# temporary prefix, builds tests/consumer (find_package(plateball) +
# target_link_libraries(consumer plateball::plateball)) against it, runs it and checks the period
# it prints (2 pi / sqrt(mu) = pi for mu = 4). In a build with OMPL it also builds tests/consumer_ompl
# (find_package(plateball COMPONENTS ompl) + plateball::ompl) and checks its exact steer.
add_test(NAME install.consumer_uses_installed_package
         COMMAND ${CMAKE_COMMAND}
                 -DBUILD_DIR=${PROJECT_BINARY_DIR}
                 -DCONSUMER_SOURCE=${PROJECT_SOURCE_DIR}/tests/consumer
                 -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/install_consumer
                 -DGENERATOR=${CMAKE_GENERATOR}
                 -DCXX_COMPILER=${CMAKE_CXX_COMPILER}
                 -DSANITIZE=${PLATEBALL_SANITIZE}
                 -DOMPL_CONSUMER_SOURCE=$<$<TARGET_EXISTS:plateball_ompl>:${PROJECT_SOURCE_DIR}/tests/consumer_ompl>
                 -P ${PROJECT_SOURCE_DIR}/tests/consumer/run_install_consumer.cmake)
# It needs the whole build tree built (cmake --install installs every target) and takes a few
# seconds (one small compile).
# (PASS_REGULAR_EXPRESSION makes ctest ignore the exit code: a FATAL_ERROR must fail by its text.)
set(install_consumer_pass "consumer: period 3\\.14159265358979")
if(TARGET plateball_ompl)
  string(APPEND install_consumer_pass ".*ompl consumer: steer exact")
endif()
set_tests_properties(install.consumer_uses_installed_package PROPERTIES
  TIMEOUT 600 LABELS install PASS_REGULAR_EXPRESSION "${install_consumer_pass}"
  FAIL_REGULAR_EXPRESSION "CMake Error")
