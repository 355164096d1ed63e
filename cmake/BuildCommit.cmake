# The git commit the sources were configured from, for the provenance of what the tools write:
# "<40 hex digits>" or "<40 hex digits>-dirty" (tracked files differed from it at configure time),
# or "not a git build" (no git, or not a git checkout: a source tarball). Local only, no network.
# Include and call tirpol_build_commit(DIR VAR), or run as a script to print it:
#   cmake -DSOURCE_DIR=DIR -P cmake/BuildCommit.cmake
function(tirpol_build_commit dir out_var)
  set(commit "not a git build")
  find_program(TIRPOL_GIT_EXECUTABLE git)
  if(TIRPOL_GIT_EXECUTABLE)
    execute_process(COMMAND ${TIRPOL_GIT_EXECUTABLE} -C ${dir} rev-parse --show-toplevel
                    OUTPUT_VARIABLE top RESULT_VARIABLE top_rc OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    # Only the project's own checkout counts, not a repository that happens to contain the tarball.
    if(top_rc EQUAL 0)
      file(REAL_PATH "${top}" top)
      file(REAL_PATH "${dir}" real_dir)
    endif()
    if(top_rc EQUAL 0 AND top STREQUAL real_dir)
      execute_process(COMMAND ${TIRPOL_GIT_EXECUTABLE} -C ${dir} rev-parse --verify HEAD
                      OUTPUT_VARIABLE head RESULT_VARIABLE head_rc OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
      if(head_rc EQUAL 0 AND head MATCHES "^[0-9a-f]+$")
        set(commit "${head}")
        execute_process(COMMAND ${TIRPOL_GIT_EXECUTABLE} -C ${dir} diff-index --quiet HEAD --
                        RESULT_VARIABLE dirty_rc OUTPUT_QUIET ERROR_QUIET)
        if(NOT dirty_rc EQUAL 0)
          string(APPEND commit "-dirty")
        endif()
      endif()
    endif()
  endif()
  set(${out_var} "${commit}" PARENT_SCOPE)
endfunction()

if(CMAKE_SCRIPT_MODE_FILE AND SOURCE_DIR)
  tirpol_build_commit(${SOURCE_DIR} commit)
  message("${commit}")
endif()
