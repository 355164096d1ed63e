# cmake -DSOURCE_DIR=<tree> -P CheckPublicHeaders.cmake
#
# Fails when a public header (<module>/include/**) includes a header that users do not get: one of a
# module's internal or testing headers (<module>/internal/include/**, <module>/testing/include/**),
# or a quoted include outside tirpol/ (a module's src/). Run by CTest (architecture.public_headers),
# so a leak like twin's old instrument.h → acquisition/internal/stage_simulator.h cannot come back.

cmake_minimum_required(VERSION 3.20)

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "CheckPublicHeaders.cmake: pass -DSOURCE_DIR=<source tree>")
endif()

# Every hidden header, by the path a source would include it with.
set(hidden)
file(GLOB hidden_roots LIST_DIRECTORIES true ${SOURCE_DIR}/*/internal/include ${SOURCE_DIR}/*/testing/include)
foreach(root ${hidden_roots})
  file(GLOB_RECURSE headers RELATIVE ${root} ${root}/*.h)
  list(APPEND hidden ${headers})
endforeach()

file(GLOB public_roots LIST_DIRECTORIES true ${SOURCE_DIR}/*/include)
set(public_count 0)
set(leaks)
foreach(root ${public_roots})
  file(GLOB_RECURSE headers ${root}/*.h)
  foreach(header ${headers})
    math(EXPR public_count "${public_count} + 1")
    file(STRINGS ${header} includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
    foreach(line ${includes})
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\".*$" "\\1" included "${line}")
      file(RELATIVE_PATH shown ${SOURCE_DIR} ${header})
      if(included IN_LIST hidden)
        list(APPEND leaks "${shown} includes the internal header ${included}")
      elseif(NOT included MATCHES "^tirpol/")
        list(APPEND leaks "${shown} includes \"${included}\", which is not a public tirpol/ header")
      endif()
    endforeach()
  endforeach()
endforeach()

list(LENGTH hidden hidden_count)
if(public_count EQUAL 0 OR hidden_count EQUAL 0)
  message(FATAL_ERROR "CheckPublicHeaders.cmake: found ${public_count} public and ${hidden_count} internal "
                      "headers under ${SOURCE_DIR}; expected some of each (wrong SOURCE_DIR?)")
endif()
if(leaks)
  list(JOIN leaks "\n  " text)
  message(FATAL_ERROR "Public headers must not include internal ones (link the internal target PRIVATE "
                      "and keep its types in src/, e.g. behind a pimpl):\n  ${text}")
endif()
message(STATUS "${public_count} public headers include none of the ${hidden_count} internal ones")
