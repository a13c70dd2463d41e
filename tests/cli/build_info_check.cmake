# Runs cmake/build_info.cmake as the build does (apps/specula/CMakeLists.txt) and checks the file
# it writes: the version given, and a commit matching EXPECT.
#   cmake -DSCRIPT=cmake/build_info.cmake -DTEMPLATE=apps/specula/build_info.cpp.in -DSOURCE_DIR=DIR
#         -DGIT_EXECUTABLE=GIT_OR_EMPTY -DOUT=FILE -DEXPECT=REGEX -P build_info_check.cmake
file(REMOVE "${OUT}")
execute_process(COMMAND "${CMAKE_COMMAND}" "-DSOURCE_DIR=${SOURCE_DIR}" "-DGIT_EXECUTABLE=${GIT_EXECUTABLE}"
                        -DVERSION=9.8.7 "-DTEMPLATE=${TEMPLATE}" "-DOUT=${OUT}" -P "${SCRIPT}"
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${SCRIPT} failed with status ${status}")
endif()
file(READ "${OUT}" text)
if(NOT text MATCHES "build_version\\(\\) noexcept { return \"9\\.8\\.7\"; }")
  message(FATAL_ERROR "no version 9.8.7 in ${OUT}:\n${text}")
endif()
if(NOT text MATCHES "build_commit\\(\\) noexcept { return \"${EXPECT}\"; }")
  message(FATAL_ERROR "the commit in ${OUT} is not ${EXPECT}:\n${text}")
endif()
