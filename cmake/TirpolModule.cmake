# tirpol_add_module(<name> [PUBLIC deps...] [PRIVATE deps...])
#
# One call per module folder: builds tirpol_<name> (alias tirpol::<name>) from <name>/src/**.cpp with
# public headers in <name>/include, and, when tests are on, tirpol_<name>_tests from
# tests/<name>/*_test.cpp, registered with CTest under the label "unit" (tests/integration/ gets
# the label "integration").

set(TIRPOL_WARNINGS -Wall -Wextra -Wconversion -Wsign-conversion -Wshadow -Wnon-virtual-dtor -Wpedantic)

function(tirpol_add_module name)
  cmake_parse_arguments(ARG "" "" "PUBLIC;PRIVATE;TEST_DEPS" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  add_library(tirpol_${name} STATIC ${sources})
  add_library(tirpol::${name} ALIAS tirpol_${name})
  target_include_directories(tirpol_${name}
    PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(tirpol_${name} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE})
  target_compile_options(tirpol_${name} PRIVATE ${TIRPOL_WARNINGS})
  # Installed and exported as tirpol::<name> (cmake/TirpolInstall.cmake).
  set_target_properties(tirpol_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON EXPORT_NAME ${name})
  set_property(GLOBAL APPEND PROPERTY TIRPOL_INSTALLED_MODULES ${name})
  tirpol_add_module_tests(${name} tirpol::${name} ${ARG_TEST_DEPS})
  tirpol_white_box_tests(${name})
endfunction()

# Test executable for a module (also used by apps/ for CLI-level tests).
function(tirpol_add_module_tests name)
  if(NOT TIRPOL_BUILD_TESTS)
    return()
  endif()
  set(dir ${PROJECT_SOURCE_DIR}/tests/${name})
  file(GLOB test_sources CONFIGURE_DEPENDS ${dir}/*_test.cpp)
  tirpol_backend_filter(test_sources ${name} ${test_sources})  # files that need a back end that is off
  if(NOT test_sources)
    return()
  endif()
  add_executable(tirpol_${name}_tests ${test_sources})
  target_link_libraries(tirpol_${name}_tests PRIVATE ${ARGN} tirpol_test_support GTest::gtest GTest::gmock GTest::gtest_main)
  target_compile_options(tirpol_${name}_tests PRIVATE ${TIRPOL_WARNINGS} -Wno-sign-conversion)
  set(label unit)
  if(name STREQUAL "integration")
    set(label integration)
  endif()
  gtest_discover_tests(tirpol_${name}_tests
    WORKING_DIRECTORY ${PROJECT_BINARY_DIR}
    PROPERTIES LABELS "${label}" TIMEOUT 600
    DISCOVERY_TIMEOUT 60)
endfunction()

# A module's own tests may include its private headers (<module>/src/*.h, by file name): each test
# file that does gets src/ on its include path, per file, so the other tests' flags (and their
# compiler-cache hits) stay the same. Other modules and apps/ never see src/.
function(tirpol_white_box_tests name)
  if(NOT TARGET tirpol_${name}_tests)
    return()
  endif()
  tirpol_white_box_sources(tirpol_${name}_tests ${name})
endfunction()

# The same for any white-box harness of a module (its tests, its benchmark): each source of
# `target` that includes a header of <module>/src/ by its path there gets that src/ on its path.
function(tirpol_white_box_sources target module)
  set(src ${PROJECT_SOURCE_DIR}/${module}/src)
  file(GLOB_RECURSE private RELATIVE ${src} ${src}/*.h)
  if(NOT private)
    return()
  endif()
  get_target_property(test_sources ${target} SOURCES)
  foreach(test ${test_sources})
    file(STRINGS ${test} includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"[^\"]+\"")
    foreach(line ${includes})
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\".*$" "\\1" included "${line}")
      if(included IN_LIST private)
        set_property(SOURCE ${test} APPEND PROPERTY INCLUDE_DIRECTORIES ${src})
        break()
      endif()
    endforeach()
  endforeach()
endfunction()
