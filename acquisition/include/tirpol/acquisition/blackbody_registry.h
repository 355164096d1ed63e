#pragma once
/// \file blackbody_registry.h
/// Opens a blackbody controller from a URI (docs/acquisition-blackbody.md):
///   fluke-4180:///dev/ttyUSB0[?baud=9600&timeout_ms=1000]   Fluke 4180 (−15…120 °C) on a serial port, 8N1
///   fluke-4181:///dev/ttyUSB0[?...]                          Fluke 4181 (35…500 °C)
///   sim://[?tau_s=60&ambient_k=296.15&noise_k=0.005&limit_k=0.05&window_s=30&model=4180&fault=none&fault_on_set=1]
///                       the same protocol served in-process by BlackbodySimulator
/// Unknown schemes or keys give InvalidArgument naming them.

#include <memory>
#include <string>

#include "tirpol/acquisition/blackbody.h"

namespace tirpol::acquisition {

Result<std::unique_ptr<BlackbodyController>> open_blackbody(const std::string& uri);

}  // namespace tirpol::acquisition
