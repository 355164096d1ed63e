# Optional device back ends (STYLE.md): TIRPOL_WITH_<NAME> = AUTO (default: on when the library is
# found, off otherwise), ON (required: configuring fails when it is missing) or OFF. Sets
# TIRPOL_HAVE_<NAME> and prints one summary line.

include(CheckIncludeFileCXX)
find_package(PkgConfig REQUIRED)

# tirpol_backend(<NAME> <description> <found-variable> <how to install>)
function(tirpol_backend name description found install)
  set(TIRPOL_WITH_${name} AUTO CACHE STRING "${description}: AUTO, ON or OFF")
  set_property(CACHE TIRPOL_WITH_${name} PROPERTY STRINGS AUTO ON OFF)
  set(mode ${TIRPOL_WITH_${name}})
  if(NOT mode MATCHES "^(AUTO|ON|OFF)$")
    message(FATAL_ERROR "TIRPOL_WITH_${name}=${mode}: expected AUTO, ON or OFF")
  endif()
  if(mode STREQUAL "OFF")
    set(have OFF)
  elseif(${found})
    set(have ON)
  elseif(mode STREQUAL "ON")
    message(FATAL_ERROR "TIRPOL_WITH_${name}=ON but ${description} was not found (${install}); "
                        "use AUTO or OFF to build without it")
  else()
    set(have OFF)
  endif()
  set(TIRPOL_HAVE_${name} ${have} PARENT_SCOPE)
endfunction()

pkg_check_modules(ARAVIS QUIET IMPORTED_TARGET aravis-0.8)
pkg_check_modules(LIBUSB QUIET IMPORTED_TARGET libusb-1.0)
check_include_file_cxx(linux/videodev2.h TIRPOL_VIDEODEV2_FOUND)
tirpol_backend(ARAVIS "Aravis 0.8 (GigE Vision / USB3 Vision cameras)" ARAVIS_FOUND "Debian: libaravis-dev")
tirpol_backend(V4L2 "V4L2 (USB UVC cameras; linux/videodev2.h)" TIRPOL_VIDEODEV2_FOUND "Debian: linux-libc-dev")
tirpol_backend(LIBUSB "libusb 1.0 (FTDI stages without the kernel driver)" LIBUSB_FOUND "Debian: libusb-1.0-0-dev")

function(tirpol_on_off var out)
  if(${var})
    set(${out} on PARENT_SCOPE)
  else()
    set(${out} off PARENT_SCOPE)
  endif()
endfunction()
tirpol_on_off(TIRPOL_HAVE_ARAVIS aravis_state)
tirpol_on_off(TIRPOL_HAVE_V4L2 v4l2_state)
tirpol_on_off(TIRPOL_HAVE_LIBUSB libusb_state)
message(STATUS "tirpol device back ends: Aravis ${aravis_state}, V4L2 ${v4l2_state}, libusb ${libusb_state} "
               "(TIRPOL_WITH_ARAVIS/V4L2/LIBUSB=AUTO|ON|OFF)")
