# `plateball view` of steer results with a rig (tests/scripts/view_rig_cli.py): the page carries the
# problem file's rig (in ball radii, also from metres) and the result's replay verdict, its strings
# escaped; a malformed rig object is refused naming the field. `view` is built where three.js is
# (web/CMakeLists.txt). (Named view_* so that cli_tests.cmake is read first.)
if(NOT TARGET plateball_cli OR NOT EXISTS ${PROJECT_SOURCE_DIR}/web/node_modules/three/build/three.module.min.js
   OR NOT EXISTS /usr/bin/python3)
  return()
endif()
add_test(NAME cli.view.rig
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/scripts/view_rig_cli.py $<TARGET_FILE:plateball_cli>
                 ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/view_rig_cli)
set_tests_properties(cli.view.rig PROPERTIES PASS_REGULAR_EXPRESSION "[0-9]+ passed, 0 failed" TIMEOUT 120 LABELS cli)
