# The documentation site (docs/, Sphinx): `cmake --build build --target docs` writes build/docs/html.
# Defined only where doxygen and sphinx-build are found (scripts/setup.sh installs Debian's), and
# never part of the default build. Warnings are errors (-W --keep-going): a broken reference, link
# or example fails the target. Needs the Python module (the API reference, the gallery) and the
# man pages (the CLI reference).
find_program(PLATEBALL_DOXYGEN doxygen)
find_program(PLATEBALL_SPHINX_BUILD sphinx-build)
if(NOT PLATEBALL_DOXYGEN OR NOT PLATEBALL_SPHINX_BUILD OR NOT TARGET plateball_python OR NOT TARGET plateball_man)
  message(STATUS "docs: target not defined (needs doxygen, sphinx-build, the Python module and help2man)")
  return()
endif()
set(PLATEBALL_DOXYGEN_DIR ${PROJECT_BINARY_DIR}/docs/doxygen)
configure_file(${PROJECT_SOURCE_DIR}/docs/Doxyfile.in ${PLATEBALL_DOXYGEN_DIR}/Doxyfile @ONLY)
file(GLOB PLATEBALL_DOC_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/docs/*.md ${PROJECT_SOURCE_DIR}/docs/*/*.md
     ${PROJECT_SOURCE_DIR}/docs/conf.py ${PROJECT_SOURCE_DIR}/examples/*.py)
add_custom_command(OUTPUT ${PLATEBALL_DOXYGEN_DIR}/xml/index.xml
  COMMAND ${CMAKE_COMMAND} -E remove_directory ${PLATEBALL_DOXYGEN_DIR}/xml
  COMMAND ${PLATEBALL_DOXYGEN} ${PLATEBALL_DOXYGEN_DIR}/Doxyfile
  DEPENDS ${PLATEBALL_PUBLIC_HEADERS} ${PROJECT_SOURCE_DIR}/docs/Doxyfile.in
  COMMENT "doxygen: XML of include/plateball/" VERBATIM)
add_custom_target(docs_doxygen DEPENDS ${PLATEBALL_DOXYGEN_DIR}/xml/index.xml)
add_custom_target(docs
  COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${PROJECT_BINARY_DIR}/python PYTHONDONTWRITEBYTECODE=1 MPLBACKEND=Agg
          PLATEBALL_DOXYGEN_XML=${PLATEBALL_DOXYGEN_DIR}/xml PLATEBALL_MAN_DIR=${PLATEBALL_MAN_DIR}
          PLATEBALL_GALLERY_OUT=${PROJECT_BINARY_DIR}/docs/gallery_files
          ${PLATEBALL_SPHINX_BUILD} -W --keep-going -q -b html -d ${PROJECT_BINARY_DIR}/docs/doctrees
          ${PROJECT_SOURCE_DIR}/docs ${PROJECT_BINARY_DIR}/docs/html
  DEPENDS docs_doxygen plateball_python plateball_man ${PLATEBALL_DOC_SOURCES}
  WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
  COMMENT "sphinx-build -W: build/docs/html" VERBATIM)
