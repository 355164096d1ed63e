# `cmake --install build [--prefix DIR]` (docs/install.md): the module libraries tirpol::<module> with
# their public headers and an exported CMake package (find_package(tirpol CONFIG)), a pkg-config file,
# the CLI and the device simulators, config/ (materials, scenes, thermal examples) where find_config
# looks for it, and the Python package. Test fixtures (acquisition's internal
# headers, test support) are not installed, and no shipped target links them (ctest
# architecture.no_test_fixture_in_production).

include(CMakePackageConfigHelpers)

get_property(tirpol_installed_modules GLOBAL PROPERTY TIRPOL_INSTALLED_MODULES)
set(tirpol_module_targets)
foreach(module ${tirpol_installed_modules})
  list(APPEND tirpol_module_targets tirpol_${module})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${module}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
          COMPONENT development FILES_MATCHING PATTERN "*.h")
endforeach()
install(TARGETS ${tirpol_module_targets} EXPORT tirpolTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

set(TIRPOL_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/tirpol CACHE STRING
    "Where the CMake package (tirpolConfig.cmake), relative to the install prefix")
install(EXPORT tirpolTargets NAMESPACE tirpol:: DESTINATION ${TIRPOL_INSTALL_CMAKEDIR} COMPONENT development)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/install/tirpolConfig.cmake.in
  ${PROJECT_BINARY_DIR}/install/tirpolConfig.cmake INSTALL_DESTINATION ${TIRPOL_INSTALL_CMAKEDIR}
  PATH_VARS CMAKE_INSTALL_DATADIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/install/tirpolConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/install/tirpolConfig.cmake ${PROJECT_BINARY_DIR}/install/tirpolConfigVersion.cmake
        DESTINATION ${TIRPOL_INSTALL_CMAKEDIR} COMPONENT development)

# pkg-config: the libraries in link order (a module before those it uses), then what they link: they are
# static archives, so the shared libraries under them are needed by every program (Requires, not
# Requires.private, whose --static expansion asks for static archives Debian does not ship, e.g. libudev).
set(TIRPOL_PC_LIBS)
set(reversed ${tirpol_installed_modules})
list(REVERSE reversed)
foreach(module ${reversed})
  string(APPEND TIRPOL_PC_LIBS " -ltirpol_${module}")
endforeach()
set(TIRPOL_PC_REQUIRES_LINK "opencv4 yaml-cpp OpenEXR libtiff-4 libpng tbb assimp cpp-httplib ompi-c")
if(TIRPOL_HAVE_ARAVIS)
  string(APPEND TIRPOL_PC_REQUIRES_LINK " aravis-0.8")
endif()
if(TIRPOL_HAVE_LIBUSB)
  string(APPEND TIRPOL_PC_REQUIRES_LINK " libusb-1.0")
endif()
file(RELATIVE_PATH TIRPOL_PC_PREFIX_FROM_PCDIR ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" TIRPOL_PC_PREFIX_FROM_PCDIR "${TIRPOL_PC_PREFIX_FROM_PCDIR}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/install/tirpol.pc.in ${PROJECT_BINARY_DIR}/install/tirpol.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/install/tirpol.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig
        COMPONENT development)

# Programs: the CLI and the device simulators (trying tirpol without hardware, docs/acquisition-*.md).
install(TARGETS tirpol tirpol-stage-sim tirpol-boson-sim tirpol-blackbody-sim
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
# find_config (core/src/source_tree.cpp) finds <prefix>/share/tirpol/config above an installed program.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/ DESTINATION ${CMAKE_INSTALL_DATADIR}/tirpol/config COMPONENT runtime)
# The Python package: python/CMakeLists.txt (it knows the interpreter's version).

# The proof: install into a fresh prefix and use it from outside the tree (tests/install/check_install.sh).
# Needs every installed target built (`cmake --build build`); label "install", run by `ctest -L install`
# and by `./run test`. Not in sanitizer builds: their instrumented libraries link only into programs built
# with the same -fsanitize flags, which is not how anyone installs tirpol.
if(TIRPOL_BUILD_TESTS AND NOT TIRPOL_SANITIZE)
  set(install_test_python)
  if(TARGET tirpol_python_extension)
    set(install_test_python ${TIRPOL_INSTALL_TEST_PYTHON})
  endif()
  add_test(NAME install.package
           COMMAND ${PROJECT_SOURCE_DIR}/tests/install/check_install.sh ${PROJECT_BINARY_DIR} ${PROJECT_SOURCE_DIR}
                   ${CMAKE_GENERATOR} ${CMAKE_CXX_COMPILER} "${CMAKE_CXX_COMPILER_LAUNCHER}" "${install_test_python}"
                   "${TIRPOL_INSTALL_PYTHONDIR}" ${PROJECT_VERSION}
                   ${CMAKE_INSTALL_LIBDIR} ${CMAKE_INSTALL_DATADIR})
  set_tests_properties(install.package PROPERTIES LABELS install TIMEOUT 600)
endif()
