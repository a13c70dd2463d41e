# cmake -D... -P component_test.cmake (arguments: see tests/install/CMakeLists.txt): the program
# SOURCE_DIR/COMPONENT.cpp (examples/components) built against the installed specula (PREFIX, made
# by install.find_package) as a project of its own that asks for COMPONENT alone and links
# specula::COMPONENT alone.
#   HIDE: packages the component must not need. find_package cannot see them
#     (CMAKE_DISABLE_FIND_PACKAGE_<package>), as if they were not installed, and none of their
#     libraries may be on the program's link line.
#   LINKED: packages whose libraries must be on the link line (the check can see a library).
#   ARGS: the program's arguments (@BUILD@: its build directory); EXPECT: text its output has.
#   HIDE, LINKED and ARGS are comma-separated.
#   EXPECT_FAILURE: instead, configuring must fail with output matching this regex (negative
#     controls: an unknown component, a component whose package is hidden).
include(${CMAKE_CURRENT_LIST_DIR}/install_support.cmake)
foreach(list HIDE LINKED ARGS)  # comma-separated on the command line
  string(REPLACE "," ";" ${list} "${${list}}")
endforeach()

# How each package's libraries appear on a link line.
set(library_PNG "libpng")
set(library_OpenEXR "libOpenEXR")
set(library_Freetype "libfreetype")
set(library_tinyobjloader "libtinyobjloader")
set(library_OpenGL "libEGL|libOpenGL")
set(library_PkgConfig "cpp-httplib")  # the one pkg-config module specula links
set(library_TBB "libtbb")

set(build "${WORK_DIR}/${COMPONENT}")
file(REMOVE_RECURSE "${build}")
consumer_configure_args(configure_args "${SOURCE_DIR}" "${build}")
list(APPEND configure_args "-DCOMPONENT=${COMPONENT}")
foreach(package IN LISTS HIDE)
  list(APPEND configure_args "-DCMAKE_DISABLE_FIND_PACKAGE_${package}=ON")
endforeach()

if(DEFINED EXPECT_FAILURE)
  execute_process(COMMAND "${CMAKE_EXE}" ${configure_args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(rc EQUAL 0)
    message(FATAL_ERROR "configuring COMPONENT=${COMPONENT} with '${HIDE}' hidden succeeded; it must fail:\n${out}")
  endif()
  if(NOT out MATCHES "${EXPECT_FAILURE}")
    message(FATAL_ERROR "configuring failed, but its output does not match '${EXPECT_FAILURE}':\n${out}")
  endif()
  message(STATUS "configuring failed as it must:\n${out}")
  return()
endif()

list(JOIN HIDE ", " hidden)
run("configuring examples/components for ${COMPONENT} with ${hidden} hidden" "${CMAKE_EXE}" ${configure_args})
check_found_in_prefix("${build}")
run("building uses_${COMPONENT}" "${CMAKE_EXE}" --build "${build}")

if(NOT GENERATOR STREQUAL "Ninja")
  message(FATAL_ERROR "this test reads the link line with `ninja -t commands`: use the Ninja generator")
endif()
run("reading the link line" "${MAKE_PROGRAM}" -C "${build}" -t commands uses_${COMPONENT})
string(REGEX MATCH "[^\n]* -o uses_${COMPONENT} [^\n]*" link_line "${run_output}")
if(NOT link_line)
  message(FATAL_ERROR "no link line for uses_${COMPONENT} in:\n${run_output}")
endif()
message(STATUS "link line:\n${link_line}")
foreach(package IN LISTS HIDE)
  if(link_line MATCHES "${library_${package}}")
    message(FATAL_ERROR "specula::${COMPONENT} links ${package} (${CMAKE_MATCH_0}), which it must not need")
  endif()
endforeach()
foreach(package IN LISTS LINKED)
  if(NOT link_line MATCHES "${library_${package}}")
    message(FATAL_ERROR "specula::${COMPONENT} does not link ${package} ('${library_${package}}')")
  endif()
endforeach()

list(TRANSFORM ARGS REPLACE "@BUILD@" "${build}")
run("running uses_${COMPONENT}" "${build}/uses_${COMPONENT}" ${ARGS})
message(STATUS "uses_${COMPONENT} output:\n${run_output}")
string(FIND "${run_output}" "${EXPECT}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "the output of uses_${COMPONENT} lacks '${EXPECT}'")
endif()
