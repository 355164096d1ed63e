#pragma once
// The message of the tirpol::Error open_camera throws for a malformed URI ("" when it does not
// throw).

#include <string>

#include "tirpol/acquisition/camera.h"
#include "tirpol/core/error.h"

namespace tirpol::test {

inline std::string open_camera_error(const std::string& uri) {
    try {
        (void)acquisition::open_camera(uri);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace tirpol::test
