# cmake -D... -P find_package_test.cmake (arguments: see tests/install/CMakeLists.txt)
# 1. cmake --install MAIN_BUILD_DIR into WORK_DIR/prefix and check the installed tree;
# 2. configure EXAMPLE_DIR as its own project with CMAKE_PREFIX_PATH=WORK_DIR/prefix, build it;
# 3. run quickstart: exit 0 and its output contains EXPECT (k of log-normalized at n = 20).

function(run)  # run(<description> <command>...): run, echo the output, fail on a non-zero exit
  list(POP_FRONT ARGN what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n  ${ARGN}\n${out}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix "${WORK_DIR}/prefix")
set(build "${WORK_DIR}/quickstart-build")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

run("cmake --install" "${CMAKE_EXE}" --install "${MAIN_BUILD_DIR}" --prefix "${prefix}")

set(expected
  "${INCLUDEDIR}/specula/models/model.h"
  "${INCLUDEDIR}/specula/lobes/log.h"
  "${LIBDIR}/libspecula.a"
  "${LIBDIR}/cmake/specula/speculaConfig.cmake"
  "${LIBDIR}/cmake/specula/speculaConfigVersion.cmake"
  "${LIBDIR}/cmake/specula/speculaTargets.cmake"
  "${BINDIR}/specula")
foreach(file IN LISTS expected)
  if(NOT EXISTS "${prefix}/${file}")
    message(FATAL_ERROR "not installed: ${prefix}/${file}")
  endif()
endforeach()
# Every public header is installed.
get_filename_component(source_dir "${EXAMPLE_DIR}" DIRECTORY)
file(GLOB_RECURSE headers RELATIVE "${source_dir}/include" "${source_dir}/include/specula/*.h")
foreach(header IN LISTS headers)
  if(NOT EXISTS "${prefix}/${INCLUDEDIR}/${header}")
    message(FATAL_ERROR "header not installed: ${prefix}/${INCLUDEDIR}/${header}")
  endif()
endforeach()
run("installed specula --help" "${prefix}/${BINDIR}/specula" --help)

set(configure_args
  -S "${EXAMPLE_DIR}" -B "${build}" -G "${GENERATOR}"
  "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}"
  "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}"
  "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
  "-DCMAKE_CXX_FLAGS=${CONSUMER_FLAGS}"
  "-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_FLAGS}"
  "-DCMAKE_PREFIX_PATH=${prefix}"
  # Only the scratch prefix may provide specula: never the build tree or a user registry.
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
if(fmt_DIR)
  list(APPEND configure_args "-Dfmt_DIR=${fmt_DIR}")  # specula's own dependency, as found
endif()
run("configuring examples/" "${CMAKE_EXE}" ${configure_args})

file(STRINGS "${build}/CMakeCache.txt" specula_dir REGEX "^specula_DIR:")
if(NOT specula_dir STREQUAL "specula_DIR:PATH=${prefix}/${LIBDIR}/cmake/specula")
  message(FATAL_ERROR "specula found elsewhere than the scratch prefix: ${specula_dir}")
endif()

run("building examples/" "${CMAKE_EXE}" --build "${build}")
run("running quickstart" "${build}/quickstart")
message(STATUS "quickstart output:\n${run_output}")
string(FIND "${run_output}" "${EXPECT}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "quickstart's output lacks ${EXPECT} (k of log-normalized at n = 20)")
endif()
