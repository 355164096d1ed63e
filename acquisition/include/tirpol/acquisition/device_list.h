#pragma once
/// \file device_list.h
/// `tirpol devices`: the cameras that can be opened now and the serial ports where a rotation
/// stage may be, with the list's JSON and text formats.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tirpol/acquisition/camera.h"

namespace tirpol::acquisition {

/// A serial port a stage may be on.
struct SerialPort {
    std::string path;    ///< the stable name when there is one (/dev/serial/by-id/…)
    std::string device;  ///< the kernel node it points to (/dev/ttyUSB0)
};

/// Under `dev` (normally /dev): serial/by-id/* first (names carry vendor and serial, stable across
/// re-plugging), then the ttyUSB* (FTDI, as in Thorlabs K-Cube/T-Cube and Elliptec bus boards) and
/// ttyACM* nodes that no by-id link already names, each group sorted by name.
std::vector<SerialPort> list_serial_ports(const std::filesystem::path& dev = "/dev");

/// The cameras (list_cameras) and serial ports found now.
struct DeviceList {
    std::vector<CameraDescriptor> cameras;
    std::vector<SerialPort> serial_ports;
};

/// Discovers cameras and serial ports (about a second: Aravis discovery).
DeviceList list_devices();

/// {"cameras": [{uri, description}], "serial_ports": [{path, device}]}.
nlohmann::json device_list_json(const DeviceList& devices);

/// The two lists as text, with the stage URI schemes a port is used in and a note when a list is
/// empty.
std::string device_list_text(const DeviceList& devices);

}  // namespace tirpol::acquisition
