#pragma once
/// \file fluke_blackbody.h
/// The Fluke 4180/4181 driver on an already open byte port (open_blackbody in blackbody.h opens it
/// by URI).

#include <chrono>
#include <memory>
#include <string>

#include "tirpol/acquisition/blackbody.h"
#include "tirpol/acquisition/internal/byte_port.h"

namespace tirpol::acquisition {

struct FlukeBlackbodyOptions {
    std::chrono::milliseconds reply_timeout{1000};
    double min_set_point_k = 0.0, max_set_point_k = 0.0;  ///< the model's range
};

/// The Fluke 4180/4181 driver on an open port: identifies the device (*IDN?), clears its error
/// queue (*CLS) and selects °C (UNIT:TEMP C). Timeout/BadReply when it does not answer as a 4180
/// does.
Result<std::unique_ptr<BlackbodyController>> open_fluke_blackbody(
    std::unique_ptr<BytePort> port, std::string uri, const FlukeBlackbodyOptions& options);

}  // namespace tirpol::acquisition
