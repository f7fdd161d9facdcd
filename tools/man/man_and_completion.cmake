# Man pages (help2man, Debian's help2man, when found) and bash completion of the command-line
# tools, built and installed with them. Included from the top-level CMakeLists.txt.
if(NOT PLATEBALL_BUILD_TOOLS OR NOT TARGET plateball_cli)
  return()
endif()
include(GNUInstallDirs)
set(PLATEBALL_COMPLETION ${PROJECT_SOURCE_DIR}/tools/completion/plateball.bash)
install(FILES ${PLATEBALL_COMPLETION} DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
        RENAME plateball)
if(TARGET isoparallel_solve)
  install(FILES ${PLATEBALL_COMPLETION} DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
          RENAME isoparallel_solve)
endif()

find_program(PLATEBALL_HELP2MAN help2man)
if(NOT PLATEBALL_HELP2MAN)
  message(STATUS "help2man not found: the man pages are not built (scripts/setup.sh installs it)")
  return()
endif()
set(PLATEBALL_MAN_DIR ${PROJECT_BINARY_DIR}/man)
set(PLATEBALL_MAN_PAGES)
function(plateball_man_page target name description)
  set(page ${PLATEBALL_MAN_DIR}/${name}.1)
  add_custom_command(OUTPUT ${page}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${PLATEBALL_MAN_DIR}
    COMMAND bash ${PROJECT_SOURCE_DIR}/tools/man/make_man.sh $<TARGET_FILE:${target}> ${name} ${page} "${description}"
    DEPENDS ${target} ${PROJECT_SOURCE_DIR}/tools/man/make_man.sh
    COMMENT "help2man: ${name}.1" VERBATIM)
  set(PLATEBALL_MAN_PAGES ${PLATEBALL_MAN_PAGES} ${page} PARENT_SCOPE)
endfunction()
plateball_man_page(plateball_cli plateball "impulsive control of a ball rolling between two plates")
if(TARGET isoparallel_solve)
  plateball_man_page(isoparallel_solve isoparallel_solve "shortest rolling path for a prescribed reorientation, and its impulses")
endif()
add_custom_target(plateball_man ALL DEPENDS ${PLATEBALL_MAN_PAGES})
install(FILES ${PLATEBALL_MAN_PAGES} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
