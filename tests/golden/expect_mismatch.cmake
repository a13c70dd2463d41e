# The negative control of golden.tour: cmake -DPYTHON=... -DSCRIPT=scripts/golden_outputs
# -DSPECULA=... -DGOLDEN=tests/golden -DWORK=scratch-dir -P expect_mismatch.cmake
# A one-command tour (`specula models`) with its recorded output copied from GOLDEN must pass
# --check unchanged (exit 0), and fail it (exit 1, naming the record) once one byte of the
# recorded stdout is changed.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/tour")
file(WRITE "${WORK}/README.md" "```console\n$ specula models\n```\n")
file(GLOB records "${GOLDEN}/tour/*-models.txt")
list(GET records 0 record)
file(READ "${record}" content)
set(check "${PYTHON}" "${SCRIPT}" --check --only tour --specula "${SPECULA}" --readme "${WORK}/README.md" --dir "${WORK}")

file(WRITE "${WORK}/tour/01-models.txt" "${content}")
execute_process(COMMAND ${check} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the unaltered record of `specula models` does not pass (exit ${rc}):\n${out}")
endif()

string(FIND "${content}" "==== stdout ====\n" at)
math(EXPR at "${at} + 17")
string(SUBSTRING "${content}" ${at} 1 byte)
set(other X)
if(byte STREQUAL "X")
  set(other Y)
endif()
string(SUBSTRING "${content}" 0 ${at} head)
math(EXPR at "${at} + 1")
string(SUBSTRING "${content}" ${at} -1 tail)
file(WRITE "${WORK}/tour/01-models.txt" "${head}${other}${tail}")
execute_process(COMMAND ${check} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "--check exited with ${rc} on a record with one byte changed; it must fail with 1:\n${out}")
endif()
if(NOT out MATCHES "DIFFERS: 01-models.txt  \\$ specula models: differs" OR NOT out MATCHES "1 of 1 outputs differ")
  message(FATAL_ERROR "--check failed without naming the altered record:\n${out}")
endif()
message(STATUS "failed as it must:\n${out}")
