# cmake -DPLATEBALL_INCLUDE_DIR=... -DPLATEBALL_LIBRARY=... -DEXAMPLE_SOURCE=... -DCONSUMER_SOURCE=...
#       -DWORK_DIR=... -DGENERATOR=... -DPROBLEM=... [-DC_COMPILER=...] [-DSANITIZE=ON] -P run_c_consumer.cmake
# Configures tests/c_consumer in WORK_DIR, builds examples/c/controller_loop.c with the C compiler
# against the build tree's library, runs it on PROBLEM and checks what it prints; then runs it on a
# missing file and checks the I/O status (5) and the message.
foreach(v PLATEBALL_INCLUDE_DIR PLATEBALL_LIBRARY EXAMPLE_SOURCE CONSUMER_SOURCE WORK_DIR GENERATOR PROBLEM)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_c_consumer.cmake: -D${v}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})

function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${step} failed (${result}):\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

set(configure_args -S ${CONSUMER_SOURCE} -B ${WORK_DIR} -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release
    -DPLATEBALL_INCLUDE_DIR=${PLATEBALL_INCLUDE_DIR} -DPLATEBALL_LIBRARY=${PLATEBALL_LIBRARY}
    -DEXAMPLE_SOURCE=${EXAMPLE_SOURCE})
if(DEFINED C_COMPILER)
  list(APPEND configure_args -DCMAKE_C_COMPILER=${C_COMPILER})
endif()
# A sanitizer build of plateball (PLATEBALL_SANITIZE) needs the sanitizer runtime in the consumer.
if(SANITIZE)
  list(APPEND configure_args "-DCMAKE_C_FLAGS=-fsanitize=address,undefined -fno-omit-frame-pointer"
       "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined")
endif()
run("configure C consumer" ${CMAKE_COMMAND} ${configure_args})
run("build C consumer" ${CMAKE_COMMAND} --build ${WORK_DIR})
run("run C consumer" ${WORK_DIR}/controller_loop ${PROBLEM})
message(STATUS "${step_output}")
if(NOT step_output MATCHES "plan: 32 impulses" OR NOT step_output MATCHES "controller: 32 impulses, status 4")
  message(FATAL_ERROR "unexpected C consumer output: ${step_output}")
endif()
execute_process(COMMAND ${WORK_DIR}/controller_loop ${WORK_DIR}/missing.json RESULT_VARIABLE result
                ERROR_VARIABLE err)
if(NOT result EQUAL 5 OR NOT err MATCHES "load: status 5: .*missing\\.json")
  message(FATAL_ERROR "a missing problem file: exit ${result}, stderr: ${err}")
endif()
message(STATUS "C consumer: ok")
