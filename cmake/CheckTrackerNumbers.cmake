# Fails when a C++ comment (or any line) of the sources cites a tracker issue number ("issue 14",
# "#31"): a reader of the code cannot follow it; say what the code or test guards instead. Run by
# CTest (style.no_tracker_numbers); an upstream project's issue is cited by its URL, and a manual's
# "Issue 7" (its revision, capitalised) is not a tracker number.
include(${CMAKE_CURRENT_LIST_DIR}/TirpolCxxSources.cmake)
tirpol_cxx_sources(sources "${SOURCE_DIR}")
list(LENGTH sources count)
set(hits)
foreach(file ${sources})
  file(STRINGS "${file}" lines REGEX "(^|[^A-Za-z])issue [0-9]+|#[0-9][0-9]+([^0-9A-Za-z_]|$)")
  foreach(line ${lines})
    file(RELATIVE_PATH name "${SOURCE_DIR}" "${file}")
    string(STRIP "${line}" line)
    list(APPEND hits "${name}: ${line}")
  endforeach()
endforeach()
if(hits)
  list(LENGTH hits n)
  list(JOIN hits "\n" text)
  message(FATAL_ERROR "${n} lines cite a tracker issue number:\n${text}")
endif()
message(STATUS "${count} files cite no tracker issue number")
