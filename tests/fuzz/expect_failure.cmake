# cmake -DREPLAY=<replay binary> -DCORPUS=<dir> -P expect_failure.cmake: passes only when the
# replay over CORPUS fails (non-zero exit or a signal) and its output names the finding and the
# input it was on (the negative control of tests/fuzz/CMakeLists.txt).
execute_process(COMMAND ${REPLAY} ${CORPUS} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "replay exit: ${result}\n${out}${err}")
if(result EQUAL 0)
  message(FATAL_ERROR "the replay passed over ${CORPUS}, which holds an input the harness aborts on")
endif()
if(NOT err MATCHES "specula fuzz finding: the magic input" OR NOT err MATCHES "magic\n")
  message(FATAL_ERROR "the replay failed without naming the finding and its input")
endif()
