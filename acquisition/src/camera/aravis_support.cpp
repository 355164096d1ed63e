#include "camera/aravis_support.h"

#include <fmt/format.h>

namespace tirpol::acquisition::aravis {

namespace {
DeviceErrorCode classify(const GError* error) {
    if (error->domain == arv_device_error_quark()) {
        switch (static_cast<ArvDeviceError>(error->code)) {
            case ARV_DEVICE_ERROR_TIMEOUT:
                return DeviceErrorCode::Timeout;
            case ARV_DEVICE_ERROR_NOT_CONNECTED:
            case ARV_DEVICE_ERROR_NOT_FOUND:
                return DeviceErrorCode::Disconnected;
            case ARV_DEVICE_ERROR_WRONG_FEATURE:
            case ARV_DEVICE_ERROR_FEATURE_NOT_FOUND:
            case ARV_DEVICE_ERROR_PROTOCOL_ERROR_NOT_IMPLEMENTED:
                return DeviceErrorCode::NotSupported;
            case ARV_DEVICE_ERROR_INVALID_PARAMETER:
            case ARV_DEVICE_ERROR_PROTOCOL_ERROR_INVALID_PARAMETER:
            case ARV_DEVICE_ERROR_PROTOCOL_ERROR_INVALID_ADDRESS:
                return DeviceErrorCode::InvalidArgument;
            case ARV_DEVICE_ERROR_PROTOCOL_ERROR:
                return DeviceErrorCode::BadReply;
            case ARV_DEVICE_ERROR_TRANSFER_ERROR:
                return DeviceErrorCode::IoError;
            default:
                return DeviceErrorCode::DeviceFault;
        }
    }
    if (error->domain == arv_gc_error_quark()) {
        switch (static_cast<ArvGcError>(error->code)) {
            case ARV_GC_ERROR_OUT_OF_RANGE:
            case ARV_GC_ERROR_ENUM_ENTRY_NOT_FOUND:
            case ARV_GC_ERROR_READ_ONLY:
                return DeviceErrorCode::InvalidArgument;
            case ARV_GC_ERROR_NODE_NOT_FOUND:
            case ARV_GC_ERROR_PROPERTY_NOT_DEFINED:
                return DeviceErrorCode::NotSupported;
            default:
                return DeviceErrorCode::DeviceFault;
        }
    }
    if (error->domain == G_IO_ERROR) return DeviceErrorCode::IoError;
    return DeviceErrorCode::DeviceFault;
}
}  // namespace

DeviceError to_device_error(const GError* error, const std::string& device,
                            const std::string& action) {
    if (error == nullptr)
        return {DeviceErrorCode::DeviceFault, fmt::format("{}: {} failed", device, action)};
    return {classify(error),
            fmt::format("{}: {}: {} (GError domain {}, code {})", device, action, error->message,
                        g_quark_to_string(error->domain), error->code)};
}

}  // namespace tirpol::acquisition::aravis
