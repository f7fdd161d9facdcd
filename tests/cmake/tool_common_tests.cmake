# Unit tests of the command-line tools' shared helpers (tools/common), built against
# plateball_tool_common (only when the tools are built).
if(NOT TARGET plateball_tool_common)
  return()
endif()
add_executable(tool_common_test ${CMAKE_CURRENT_SOURCE_DIR}/tools/tool_common_test.cc)
target_link_libraries(tool_common_test PRIVATE plateball_tool_common plateball GTest::gtest_main)
target_compile_options(tool_common_test PRIVATE ${PLATEBALL_WARNINGS})
gtest_discover_tests(tool_common_test DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 120)

# The tools' helpers: streamed samples, progress, figure size, SI units, figure axes and legend.
add_executable(ux_common_test ${CMAKE_CURRENT_SOURCE_DIR}/tools/ux_common_test.cc)
target_link_libraries(ux_common_test PRIVATE plateball_tool_common plateball GTest::gtest_main)
target_compile_definitions(ux_common_test PRIVATE PLATEBALL_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
target_compile_options(ux_common_test PRIVATE ${PLATEBALL_WARNINGS})
gtest_discover_tests(ux_common_test DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 120)
