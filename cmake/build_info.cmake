# Writes the CLI's build information (apps/specula/build_info.h): the version and the git commit.
#   cmake -DSOURCE_DIR=... -DGIT_EXECUTABLE=... -DVERSION=... -DTEMPLATE=... -DOUT=... -P build_info.cmake
# Run at every build by the target specula_build_info (apps/specula/CMakeLists.txt). The commit is
# `git rev-parse --short HEAD` of SOURCE_DIR when SOURCE_DIR is the top of a git checkout, and
# "unknown" otherwise: no git, a source tarball, or a tree unpacked inside some other repository.
# configure_file rewrites OUT only when its text changes, so a new commit recompiles that one
# small file and relinks the CLI, nothing else.
set(SPECULA_GIT_COMMIT "unknown")
if(GIT_EXECUTABLE)
  execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${SOURCE_DIR}" rev-parse --show-toplevel
                  RESULT_VARIABLE top_status OUTPUT_VARIABLE top OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(top_status EQUAL 0)
    file(REAL_PATH "${top}" top)
    file(REAL_PATH "${SOURCE_DIR}" source)
    if(top STREQUAL source)
      execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${SOURCE_DIR}" rev-parse --short HEAD
                      RESULT_VARIABLE status OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
      if(status EQUAL 0 AND commit MATCHES "^[0-9a-f]+$")
        set(SPECULA_GIT_COMMIT "${commit}")
      endif()
    endif()
  endif()
endif()
set(SPECULA_VERSION "${VERSION}")
configure_file("${TEMPLATE}" "${OUT}" @ONLY)
