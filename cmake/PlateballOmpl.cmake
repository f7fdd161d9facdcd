# Optional exact steering for OMPL (include/plateball/ompl/steering.h, src/ompl/, examples/ompl/):
# built when OMPL's CMake package is found (Debian's libompl-dev, OMPL 1.5; scripts/setup.sh installs
# it). OMPL's types stay in that header and the plateball_ompl library; libplateball does not depend
# on OMPL. Not in sanitizer or fuzz builds, like MuJoCo: the uninstrumented libompl is outside the
# sanitizers' view.
option(PLATEBALL_OMPL "Build the OMPL exact steering (plateball_ompl) when OMPL is found" ON)
set(PLATEBALL_WITH_OMPL OFF)
if(PLATEBALL_OMPL AND NOT PLATEBALL_SANITIZE AND NOT PLATEBALL_FUZZ)
  find_package(ompl QUIET)
  if(OMPL_FOUND AND OMPL_VERSION VERSION_GREATER_EQUAL 1.5)
    # Debian's omplConfig.cmake (1.5.2) lists Boost's serialization, filesystem and system libraries
    # and ODE among OMPL_LIBRARIES, whose -dev packages libompl-dev does not pull in; libompl.so names
    # its own runtime dependencies, so only the libraries that exist are linked.
    set(_ompl_libraries)
    foreach(_lib IN LISTS OMPL_LIBRARIES)
      if(IS_ABSOLUTE "${_lib}" AND EXISTS "${_lib}")
        list(APPEND _ompl_libraries "${_lib}")
      endif()
    endforeach()
    add_library(plateball_ompl STATIC ${PROJECT_SOURCE_DIR}/src/ompl/steering.cc)
    add_library(plateball::ompl ALIAS plateball_ompl)
    target_include_directories(plateball_ompl PRIVATE ${PROJECT_SOURCE_DIR}/src)
    # OMPL's headers as system headers: their warnings are not plateball's. OMPL's paths are the
    # build's only: the installed package finds OMPL again (plateballConfig.cmake, component ompl).
    foreach(_dir IN LISTS OMPL_INCLUDE_DIRS)
      target_include_directories(plateball_ompl SYSTEM PUBLIC $<BUILD_INTERFACE:${_dir}>)
    endforeach()
    target_link_libraries(plateball_ompl PUBLIC plateball)
    foreach(_lib IN LISTS _ompl_libraries)
      target_link_libraries(plateball_ompl PUBLIC $<BUILD_INTERFACE:${_lib}>)
    endforeach()
    target_compile_options(plateball_ompl PRIVATE ${PLATEBALL_WARNINGS})
    set_target_properties(plateball_ompl PROPERTIES POSITION_INDEPENDENT_CODE ON EXPORT_NAME ompl)
    # Installed as the package's component `ompl`: find_package(plateball COMPONENTS ompl) gives
    # plateball::ompl (the static library, the header plateball/ompl/steering.h and OMPL's usage).
    install(TARGETS plateball_ompl EXPORT plateballOmplTargets
      ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
      INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    install(FILES ${PROJECT_SOURCE_DIR}/include/plateball/ompl/steering.h
      DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/plateball/ompl)
    install(EXPORT plateballOmplTargets NAMESPACE plateball::
      DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/plateball)
    add_executable(ompl_plan_around_disk ${PROJECT_SOURCE_DIR}/examples/ompl/plan_around_disk.cc)
    target_link_libraries(ompl_plan_around_disk PRIVATE plateball_ompl)
    target_compile_options(ompl_plan_around_disk PRIVATE ${PLATEBALL_WARNINGS})
    set(PLATEBALL_WITH_OMPL ON)
    message(STATUS "plateball_ompl: OMPL ${OMPL_VERSION} found, the exact steering for OMPL is built")
  else()
    message(STATUS "plateball_ompl: OMPL >= 1.5 not found (Debian: libompl-dev), the exact steering for OMPL is not built")
  endif()
endif()
