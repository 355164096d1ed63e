#include "tirpol/acquisition/result.h"

namespace tirpol::acquisition {

const char* to_string(DeviceErrorCode code) {
    switch (code) {
        case DeviceErrorCode::Timeout:
            return "timeout";
        case DeviceErrorCode::BadReply:
            return "bad reply";
        case DeviceErrorCode::DeviceFault:
            return "device fault";
        case DeviceErrorCode::Disconnected:
            return "disconnected";
        case DeviceErrorCode::NotSupported:
            return "not supported";
        case DeviceErrorCode::InvalidArgument:
            return "invalid argument";
        case DeviceErrorCode::IoError:
            return "I/O error";
        case DeviceErrorCode::Stopped:
            return "stopped";
    }
    return "unknown device error";
}

}  // namespace tirpol::acquisition
