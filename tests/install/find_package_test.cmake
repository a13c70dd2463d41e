# cmake -D... -P find_package_test.cmake (arguments: see tests/install/CMakeLists.txt)
# 1. cmake --install MAIN_BUILD_DIR into PREFIX and check the installed tree: every public header,
#    every component's library and export file, the package files, the CLI;
# 2. configure EXAMPLE_DIR as its own project (find_package(specula), specula::specula: every
#    component), build it;
# 3. run quickstart: exit 0 and its output contains EXPECT (k of log-normalized at n = 20).
# The components one by one: component_test.cmake.
include(${CMAKE_CURRENT_LIST_DIR}/install_support.cmake)
string(REPLACE "," ";" COMPONENTS "${COMPONENTS}")  # comma-separated on the command line

set(build "${WORK_DIR}/quickstart-build")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

run("cmake --install" "${CMAKE_EXE}" --install "${MAIN_BUILD_DIR}" --prefix "${PREFIX}")

set(expected
  "${INCLUDEDIR}/specula/models/model.h"
  "${INCLUDEDIR}/specula/lobes/log.h"
  "${LIBDIR}/cmake/specula/speculaConfig.cmake"
  "${LIBDIR}/cmake/specula/speculaConfigVersion.cmake"
  "${LIBDIR}/cmake/specula/specula-components.cmake"
  "${LIBDIR}/cmake/specula/specula-all-targets.cmake"
  "${BINDIR}/specula")
foreach(component IN LISTS COMPONENTS)
  list(APPEND expected "${LIBDIR}/libspecula_${component}.a" "${LIBDIR}/cmake/specula/specula-${component}-targets.cmake")
endforeach()
foreach(file IN LISTS expected)
  if(NOT EXISTS "${PREFIX}/${file}")
    message(FATAL_ERROR "not installed: ${PREFIX}/${file}")
  endif()
endforeach()
# Every public header is installed.
get_filename_component(source_dir "${EXAMPLE_DIR}" DIRECTORY)
file(GLOB_RECURSE headers RELATIVE "${source_dir}/include" "${source_dir}/include/specula/*.h")
foreach(header IN LISTS headers)
  if(NOT EXISTS "${PREFIX}/${INCLUDEDIR}/${header}")
    message(FATAL_ERROR "header not installed: ${PREFIX}/${INCLUDEDIR}/${header}")
  endif()
endforeach()
run("installed specula --help" "${PREFIX}/${BINDIR}/specula" --help)

consumer_configure_args(configure_args "${EXAMPLE_DIR}" "${build}")
run("configuring examples/" "${CMAKE_EXE}" ${configure_args})
check_found_in_prefix("${build}")
run("building examples/" "${CMAKE_EXE}" --build "${build}")
run("running quickstart" "${build}/quickstart")
message(STATUS "quickstart output:\n${run_output}")
string(FIND "${run_output}" "${EXPECT}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "quickstart's output lacks ${EXPECT} (k of log-normalized at n = 20)")
endif()
