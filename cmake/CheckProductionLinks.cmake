# cmake -DLINKS_FILE=<build>/architecture/production_links.txt -P CheckProductionLinks.cmake
#
# Fails when a shipped target (the module libraries, the CLI, the simulator programs, the Python
# extension) links a test fixture (a *_testing target), directly or through another target. The file
# is written at configure time by tirpol_write_production_links (cmake/TirpolProductionLinks.cmake).
# Run by CTest (architecture.no_test_fixture_in_production).

cmake_minimum_required(VERSION 3.20)

if(NOT LINKS_FILE OR NOT EXISTS "${LINKS_FILE}")
  message(FATAL_ERROR "CheckProductionLinks.cmake: pass -DLINKS_FILE=<existing file> (got '${LINKS_FILE}')")
endif()
file(STRINGS ${LINKS_FILE} lines)
list(LENGTH lines target_count)
if(target_count LESS 3)
  message(FATAL_ERROR "CheckProductionLinks.cmake: ${LINKS_FILE} lists ${target_count} shipped targets; "
                      "expected the module libraries and the CLI (was it written at configure time?)")
endif()
set(offences)
foreach(line ${lines})
  string(REGEX REPLACE "^([^:]+):.*$" "\\1" target "${line}")
  string(REGEX REPLACE "^[^:]+:[ ]*" "" links "${line}")
  string(REPLACE " " ";" links "${links}")
  foreach(link ${links})
    if(link MATCHES "_testing$")
      list(APPEND offences "${target} links the test fixture ${link}")
    endif()
  endforeach()
endforeach()
if(offences)
  list(JOIN offences "\n  " text)
  message(FATAL_ERROR "Shipped targets must not link test fixtures (make what production needs public "
                      "API of the module, e.g. acquisition/sim/*.h):\n  ${text}")
endif()
message(STATUS "${target_count} shipped targets link no *_testing target")
