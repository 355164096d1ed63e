# `./run package` (cpack -G DEB in the build folder): one Debian package, tirpol_<version>_<arch>.deb,
# with everything `cmake --install` puts in place (cmake/TirpolInstall.cmake) under /usr. Its
# dependencies are of two kinds (docs/install.md):
#  - the shared libraries the programs and the Python extension load, found by dpkg-shlibdeps
#    (libopencv-core406, libembree3-3, ...);
#  - what the installed static libraries, their headers, the CMake package and pkg-config file need to
#    build a downstream program, and what the Python package imports: the Debian packages of ./run's
#    PACKAGES list, named below. tests/install/check_deb.sh fails when one is not in that list or apt
#    cannot resolve it.

set(TIRPOL_DEB_DEVELOPMENT_DEPENDS
    libeigen3-dev libfmt-dev libspdlog-dev nlohmann-json3-dev libopenexr-dev libopencv-dev
    libyaml-cpp-dev libtiff-dev libpng-dev zlib1g-dev libembree-dev libtbb-dev libassimp-dev libceres-dev
    libgoogle-glog-dev libopenmpi-dev libcpp-httplib-dev pkg-config)
if(TIRPOL_HAVE_ARAVIS)
  list(APPEND TIRPOL_DEB_DEVELOPMENT_DEPENDS libaravis-dev)
endif()
if(TIRPOL_HAVE_LIBUSB)
  list(APPEND TIRPOL_DEB_DEVELOPMENT_DEPENDS libusb-1.0-0-dev)
endif()
set(TIRPOL_DEB_PYTHON_DEPENDS)
if(TARGET tirpol_python_extension AND TIRPOL_INSTALL_PYTHONDIR MATCHES "python3\\.([0-9]+)/")
  # The extension is built for one interpreter version (lib/python3.11/dist-packages).
  math(EXPR tirpol_python_next_minor "${CMAKE_MATCH_1} + 1")
  set(TIRPOL_DEB_PYTHON_DEPENDS "python3 (>= 3.${CMAKE_MATCH_1})" "python3 (<< 3.${tirpol_python_next_minor})"
      python3-numpy)
endif()
list(JOIN TIRPOL_DEB_DEVELOPMENT_DEPENDS ", " tirpol_deb_development)
list(JOIN TIRPOL_DEB_PYTHON_DEPENDS ", " tirpol_deb_python)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "${tirpol_deb_development}")
if(tirpol_deb_python)
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", ${tirpol_deb_python}")
  # Maintainer scripts that byte-compile the Python package on install and remove the compiled files
  # before removal, as dh_python3 does for Debian's Python packages: without them a Python run as root
  # wrote __pycache__ into dist-packages and `apt remove tirpol` left that folder behind (seen on a clean
  # Debian 12 root, tests/install/check_clean_debian.sh).
  set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_SOURCE_DIR}/cmake/package/postinst
                                         ${PROJECT_SOURCE_DIR}/cmake/package/prerm)
  set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
endif()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME tirpol)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_CONTACT "tirpol developers")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_PACKAGE_DIRECTORY ${PROJECT_BINARY_DIR}/packages)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # tirpol_0.1.0_amd64.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
    "Thermal-infrared polarimetry: acquisition, calibration, Stokes imaging, pBRDF fitting,\n\
polarimetric rendering and measured-versus-simulated reports. The tirpol CLI and device simulators,\n\
the module libraries with a CMake package and pkg-config file, the material library and the Python\n\
package.")
include(CPack)

# The proof: build the package, check its control fields against ./run and apt, extract it into a fresh
# folder and use it from there (tests/install/check_deb.sh, which reuses check_install.sh). Label
# "install" like install.package; needs every installed target built.
if(TIRPOL_BUILD_TESTS AND NOT TIRPOL_SANITIZE)
  add_test(NAME install.deb
           COMMAND ${PROJECT_SOURCE_DIR}/tests/install/check_deb.sh ${PROJECT_BINARY_DIR} ${PROJECT_SOURCE_DIR}
                   ${CMAKE_GENERATOR} ${CMAKE_CXX_COMPILER} "${CMAKE_CXX_COMPILER_LAUNCHER}" "${install_test_python}"
                   "${TIRPOL_INSTALL_PYTHONDIR}" ${PROJECT_VERSION}
                   ${CMAKE_INSTALL_LIBDIR} ${CMAKE_INSTALL_DATADIR})
  set_tests_properties(install.deb PROPERTIES LABELS install TIMEOUT 900 RUN_SERIAL ON)
endif()
