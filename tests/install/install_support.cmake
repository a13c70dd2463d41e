# What the install tests share (included by find_package_test.cmake and component_test.cmake).

# run(<description> <command>...): run, fail on a non-zero exit with the output; run_output is
# the output (stdout and stderr).
function(run)
  list(POP_FRONT ARGN what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n  ${ARGN}\n${out}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

# consumer_configure_args(<var> <source dir> <build dir>): the arguments that configure a project
# of its own against PREFIX alone, compiled like the library (CONSUMER_FLAGS: its sanitizers).
function(consumer_configure_args var source build)
  set(args
    -S "${source}" -B "${build}" -G "${GENERATOR}"
    "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}"
    "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}"
    "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
    "-DCMAKE_CXX_FLAGS=${CONSUMER_FLAGS}"
    "-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_FLAGS}"
    "-DCMAKE_PREFIX_PATH=${PREFIX}"
    # Only the scratch prefix may provide specula: never the build tree or a user registry.
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
  if(fmt_DIR)
    list(APPEND args "-Dfmt_DIR=${fmt_DIR}")  # specula's own dependency, as found
  endif()
  set(${var} ${args} PARENT_SCOPE)
endfunction()

# check_found_in_prefix(<build dir>): fails unless the consumer found specula in PREFIX.
function(check_found_in_prefix build)
  file(STRINGS "${build}/CMakeCache.txt" specula_dir REGEX "^specula_DIR:")
  if(NOT specula_dir STREQUAL "specula_DIR:PATH=${PREFIX}/${LIBDIR}/cmake/specula")
    message(FATAL_ERROR "specula found elsewhere than the scratch prefix: ${specula_dir}")
  endif()
endfunction()
