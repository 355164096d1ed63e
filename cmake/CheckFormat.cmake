# Fails when a C++ source or header under the modules, apps, tests, bench, fuzz or python differs from what
# clang-format makes of it (.clang-format: one column limit everywhere). Run by CTest (style.clang_format).
# clang-format-14 is in ./run's package list: its absence is a failure, not a skip.
find_program(CLANG_FORMAT NAMES clang-format-14 clang-format)
if(NOT CLANG_FORMAT)
  message(FATAL_ERROR "clang-format-14 not found: ./run installs it (package clang-format-14)")
endif()
include(${CMAKE_CURRENT_LIST_DIR}/TirpolCxxSources.cmake)
tirpol_cxx_sources(sources "${SOURCE_DIR}")
list(LENGTH sources count)
execute_process(COMMAND ${CLANG_FORMAT} --style=file --dry-run -Werror ${sources}
                WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE rc ERROR_VARIABLE complaints)
if(NOT rc EQUAL 0)
  string(REGEX MATCHALL "[^\n]*: error: [^\n]*" lines "${complaints}")
  list(LENGTH lines n)
  list(SUBLIST lines 0 20 first)
  string(REPLACE ";" "\n" first "${first}")
  message(FATAL_ERROR "${n} formatting differences (run clang-format-14 -i on the files):\n${first}")
endif()
message(STATUS "${count} files formatted as .clang-format says")
