# cmake -DSOURCE_DIR=<tree> -P TestPublicHeaderUse.cmake
#
# The check of cmake/CheckPublicHeaderUse.cmake must fail on the fixture tree
# tests/data/architecture/public_header_use/ (its README.md) and name exactly the two headers no
# other module uses: one its own sources and tests include, one only a benchmark and a fuzz target
# include. Run by CTest (architecture.public_headers_used_fixture), so the check cannot pass
# everything without a test failing.

cmake_minimum_required(VERSION 3.20)

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "TestPublicHeaderUse.cmake: pass -DSOURCE_DIR=<source tree>")
endif()
set(fixture ${SOURCE_DIR}/tests/data/architecture/public_header_use)
execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${fixture}
                        -P ${SOURCE_DIR}/cmake/CheckPublicHeaderUse.cmake
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(result EQUAL 0)
  message(FATAL_ERROR "CheckPublicHeaderUse.cmake passed on ${fixture}, which has two public "
                      "headers no other module uses:\n${output}")
endif()
foreach(expected own_only.h bench_only.h)
  if(NOT output MATCHES "alpha/include/tirpol/alpha/${expected}")
    message(FATAL_ERROR "CheckPublicHeaderUse.cmake did not name ${expected}:\n${output}")
  endif()
endforeach()
foreach(used used.h member.h)
  if(output MATCHES "alpha/include/tirpol/alpha/${used}")
    message(FATAL_ERROR "CheckPublicHeaderUse.cmake named ${used}, which module beta uses:\n${output}")
  endif()
endforeach()
message(STATUS "CheckPublicHeaderUse.cmake names the two unused headers of ${fixture}")
