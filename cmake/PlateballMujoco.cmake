# Optional MuJoCo digital twin (`plateball rig export|replay`, tools/rig/): built when MuJoCo's CMake
# package is found (Debian's libmujoco-dev, C API; scripts/setup.sh installs it). Not in sanitizer or
# fuzz builds, like MPI: the uninstrumented libmujoco's allocations are outside the sanitizers' view.
option(PLATEBALL_MUJOCO "Build the MuJoCo twin (plateball rig) when MuJoCo is found" ON)
set(PLATEBALL_WITH_MUJOCO OFF)
if(PLATEBALL_MUJOCO AND TARGET plateball_cli AND NOT PLATEBALL_SANITIZE AND NOT PLATEBALL_FUZZ)
  find_package(mujoco CONFIG QUIET)
  if(mujoco_FOUND AND TARGET mujoco::mujoco)
    # Debian's mujocoTargets.cmake (2.2.2) lists /usr/include/libqhull_r/ (libqhull-dev) among its
    # include directories; the C API's headers do not need it, and CMake rejects a missing one.
    get_target_property(_mujoco_includes mujoco::mujoco INTERFACE_INCLUDE_DIRECTORIES)
    set(_mujoco_existing)
    foreach(_dir IN LISTS _mujoco_includes)
      if(EXISTS "${_dir}")
        list(APPEND _mujoco_existing "${_dir}")
      endif()
    endforeach()
    set_target_properties(mujoco::mujoco PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_mujoco_existing}")
    add_library(plateball_rig STATIC ${PROJECT_SOURCE_DIR}/tools/rig/rig_plan.cc
                                     ${PROJECT_SOURCE_DIR}/tools/rig/mujoco_twin.cc
                                     ${PROJECT_SOURCE_DIR}/tools/rig/twin_loop.cc)
    target_include_directories(plateball_rig PUBLIC ${PROJECT_SOURCE_DIR}/tools)
    target_link_libraries(plateball_rig PUBLIC plateball_tool_common plateball mujoco::mujoco)
    target_compile_options(plateball_rig PRIVATE ${PLATEBALL_WARNINGS})
    target_sources(plateball_cli PRIVATE ${PROJECT_SOURCE_DIR}/tools/rig/cmd_rig.cc ${PROJECT_SOURCE_DIR}/tools/rig/loop_command.cc)
    target_link_libraries(plateball_cli PRIVATE plateball_rig)
    set(PLATEBALL_WITH_MUJOCO ON)
    message(STATUS "plateball rig: MuJoCo ${mujoco_VERSION} found, the digital twin is built")
  else()
    message(STATUS "plateball rig: MuJoCo not found (Debian: libmujoco-dev), the digital twin is not built")
  endif()
endif()
