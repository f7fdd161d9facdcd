# cmake -DBUILD_DIR=... -DCONSUMER_SOURCE=... -DWORK_DIR=... -DGENERATOR=... [-DCXX_COMPILER=...]
#       [-DSANITIZE=ON] [-DOMPL_CONSUMER_SOURCE=...] -P run_install_consumer.cmake
# Installs the plateball build tree into WORK_DIR/prefix, configures and builds the consumer
# project against it (CMAKE_PREFIX_PATH = the prefix only), runs it and checks its output. With
# OMPL_CONSUMER_SOURCE (a build with OMPL) it does the same for the OMPL component's consumer.
foreach(v BUILD_DIR CONSUMER_SOURCE WORK_DIR GENERATOR)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_install_consumer.cmake: -D${v}=... is required")
  endif()
endforeach()

set(prefix ${WORK_DIR}/prefix)
set(consumer_build ${WORK_DIR}/build)
file(REMOVE_RECURSE ${WORK_DIR})

function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${step} failed (${result}):\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

run("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
if(NOT EXISTS ${prefix}/include/plateball/free_motion.h)
  message(FATAL_ERROR "install: no headers under ${prefix}/include/plateball")
endif()
file(GLOB_RECURSE config_files ${prefix}/*/plateballConfig.cmake)
if(NOT config_files)
  message(FATAL_ERROR "install: no plateballConfig.cmake under ${prefix}")
endif()

set(configure_args -S ${CONSUMER_SOURCE} -B ${consumer_build} -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON)
if(DEFINED CXX_COMPILER)
  list(APPEND configure_args -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
endif()
# A sanitizer build of plateball (PLATEBALL_SANITIZE) needs the sanitizer runtime in the consumer.
if(SANITIZE)
  list(APPEND configure_args "-DCMAKE_CXX_FLAGS=-fsanitize=address,undefined -fno-omit-frame-pointer"
       "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined")
endif()
run("configure consumer" ${CMAKE_COMMAND} ${configure_args})
# The package must come from the install prefix, never from the build tree.
string(FIND "${step_output}" "plateball_DIR=${prefix}/" found)
if(found EQUAL -1)
  message(FATAL_ERROR "consumer found plateball outside ${prefix}:\n${step_output}")
endif()
run("build consumer" ${CMAKE_COMMAND} --build ${consumer_build})
run("run consumer" ${consumer_build}/consumer)
message(STATUS "${step_output}")
if(NOT step_output MATCHES "consumer: period 3\\.14159265358979")
  message(FATAL_ERROR "unexpected consumer output: ${step_output}")
endif()

if(NOT OMPL_CONSUMER_SOURCE)
  return()
endif()
# The OMPL component: its header and static library installed, plateball::ompl exported.
if(NOT EXISTS ${prefix}/include/plateball/ompl/steering.h)
  message(FATAL_ERROR "install: no plateball/ompl/steering.h under ${prefix}/include")
endif()
file(GLOB_RECURSE ompl_targets ${prefix}/*/plateballOmplTargets.cmake)
if(NOT ompl_targets)
  message(FATAL_ERROR "install: no plateballOmplTargets.cmake under ${prefix}")
endif()
set(ompl_args ${configure_args})
list(TRANSFORM ompl_args REPLACE "^${CONSUMER_SOURCE}$" "${OMPL_CONSUMER_SOURCE}")
list(TRANSFORM ompl_args REPLACE "^${consumer_build}$" "${WORK_DIR}/ompl_build")
run("configure OMPL consumer" ${CMAKE_COMMAND} ${ompl_args})
string(FIND "${step_output}" "plateball_DIR=${prefix}/" found)
if(found EQUAL -1)
  message(FATAL_ERROR "OMPL consumer found plateball outside ${prefix}:\n${step_output}")
endif()
run("build OMPL consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/ompl_build)
run("run OMPL consumer" ${WORK_DIR}/ompl_build/ompl_consumer)
message(STATUS "${step_output}")
if(NOT step_output MATCHES "ompl consumer: steer exact")
  message(FATAL_ERROR "unexpected OMPL consumer output: ${step_output}")
endif()
