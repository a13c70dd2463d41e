# Unity builds (docs/testing.md, "Build less"): CMake compiles a target's sources BATCH at a time
# as one translation unit. Under the sanitizers most of a file's compile time is code for the
# inline functions of the headers it uses (CLI11, fmt, nlohmann-json, GoogleTest, RapidCheck),
# emitted again in every file that uses them; a batch emits them once. Used for the targets that
# are many thin files over the same heavy headers (the CLI, the tests, the Python module). The
# libraries' own files stay one unit each, so that a change to one recompiles that file alone.
# Sources in one batch share a translation unit: file-local names (anonymous namespaces, static
# functions) must differ between the files of a target.
option(SPECULA_UNITY "Compile the CLI, the tests and the Python module as unity batches" ON)

# specula_unity(<target> <batch>): <target>'s sources compiled <batch> files per unit.
function(specula_unity target batch)
  if(SPECULA_UNITY)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${batch})
  endif()
endfunction()
