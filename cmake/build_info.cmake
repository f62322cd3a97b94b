# Writes OUT (the build's identity: mlshell's version and the source commit) for
# src/io/build_info.cpp. Run at every build (target mlshell_build_info), so that the commit
# follows the checkout; configure_file leaves OUT untouched when nothing changed, so that an
# unchanged commit recompiles nothing.
#
#   cmake -DSOURCE_DIR=... -DVERSION=... -DOUT=... -P build_info.cmake
set(commit "unknown")
find_package(Git QUIET)
if(GIT_FOUND AND EXISTS "${SOURCE_DIR}/.git")
  # The commit, and "-modified" when tracked files differ from it.
  execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${SOURCE_DIR}" describe --always
                          --dirty=-modified --abbrev=12 --exclude=*
                  OUTPUT_VARIABLE described OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE failed ERROR_QUIET)
  if(NOT failed AND described)
    set(commit "${described}")
  endif()
endif()
set(MLSHELL_VERSION "${VERSION}")
set(MLSHELL_COMMIT "${commit}")
configure_file("${CMAKE_CURRENT_LIST_DIR}/build_info.hpp.in" "${OUT}" @ONLY)
