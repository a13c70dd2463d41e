# specula_skip_unrunnable_hwy_targets(): the sanitizer build compiles the SIMD kernels only for the
# x86 targets this machine runs. Its tests run every target the CPU has (simd::runnable_targets),
# so a target the CPU lacks is compile time that no test reaches; the release build keeps them all.
function(specula_skip_unrunnable_hwy_targets)
  if(NOT CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64")
    return()
  endif()
  try_run(run_result compile_result ${CMAKE_BINARY_DIR}/hwy_runnable_targets
    ${PROJECT_SOURCE_DIR}/cmake/hwy_runnable_targets.cpp
    LINK_LIBRARIES hwy::hwy
    RUN_OUTPUT_VARIABLE runnable)
  if(NOT compile_result OR NOT run_result EQUAL 0 OR NOT runnable MATCHES "^[0-9]+$")
    message(STATUS "Highway: could not read this machine's targets; compiling every target")
    return()
  endif()
  # Highway's bits (hwy/detect_targets.h): AVX3_DL 1 << 7, AVX3 1 << 8, AVX2 1 << 9, SSE4 1 << 11,
  # SSSE3 1 << 12.
  set(skipped "")
  foreach(target AVX3_DL:7 AVX3:8 AVX2:9 SSE4:11 SSSE3:12)
    string(REPLACE ":" ";" pair ${target})
    list(GET pair 0 name)
    list(GET pair 1 bit)
    math(EXPR has "(${runnable} >> ${bit}) & 1")
    if(NOT has)
      list(APPEND skipped HWY_${name})
    endif()
  endforeach()
  if(skipped)
    list(JOIN skipped "|" disabled)
    list(JOIN skipped ", " named)
    message(STATUS "Highway: this machine does not run ${named}; the sanitizer build skips them")
    add_compile_definitions("HWY_DISABLED_TARGETS=(${disabled})")
  endif()
endfunction()
