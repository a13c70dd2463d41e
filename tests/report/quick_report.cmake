# The fixture test report.quick_report (tests/report/CMakeLists.txt): one quick report with the
# user's lobes, as a user makes it, for the suites that read it (quick_report.h).
#   cmake -DSPECULA=cli -DMODELS=user_lobes.toml -DFOLDER=dir -P quick_report.cmake
# Writes FOLDER/report and FOLDER/{stdout,stderr,exit_code}; fails when the CLI does, with its
# stderr, so that the reason is in this test's output (the suites then check the same files).
file(REMOVE_RECURSE "${FOLDER}")
file(MAKE_DIRECTORY "${FOLDER}")
execute_process(COMMAND "${SPECULA}" --models "${MODELS}" report --quick --out "${FOLDER}/report"
  OUTPUT_FILE "${FOLDER}/stdout" ERROR_FILE "${FOLDER}/stderr" RESULT_VARIABLE rc)
file(WRITE "${FOLDER}/exit_code" "${rc}\n")
if(NOT rc EQUAL 0)
  file(READ "${FOLDER}/stderr" err)
  message(FATAL_ERROR "specula report --quick exited with ${rc}:\n${err}")
endif()
