# cmake -DREADME=<README.md> -DEXAMPLE=<quickstart.cpp> -P readme_example_test.cmake
# Fails unless README contains EXAMPLE's text exactly (so the README's example compiles and runs).
foreach(file README EXAMPLE)
  if(NOT EXISTS "${${file}}")
    message(FATAL_ERROR "${${file}} does not exist")
  endif()
endforeach()
file(READ "${README}" readme)
file(READ "${EXAMPLE}" example)
string(FIND "${readme}" "${example}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${README} does not contain the text of ${EXAMPLE} verbatim; "
                      "paste the file into it unchanged:\n${example}")
endif()
message(STATUS "${README} quotes ${EXAMPLE} at offset ${at}")
