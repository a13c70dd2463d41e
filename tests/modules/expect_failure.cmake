# cmake -DPYTHON=... -DSCRIPT=scripts/check_modules.py -DROOT=fixture -DEXPECT=regex -P expect_failure.cmake:
# the module check of the fixture ROOT must fail with exit status 1 (a violation, not a crash of
# the script) and print a line matching EXPECT.
execute_process(COMMAND "${PYTHON}" "${SCRIPT}" --root "${ROOT}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "the module check of ${ROOT} exited with ${rc}; it must fail with 1:\n${out}")
endif()
if(NOT out MATCHES "${EXPECT}")
  message(FATAL_ERROR "the module check of ${ROOT} failed without a line matching '${EXPECT}':\n${out}")
endif()
message(STATUS "failed as it must:\n${out}")
