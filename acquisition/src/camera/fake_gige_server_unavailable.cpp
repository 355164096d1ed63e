// FakeGigECameraServer in a build without Aravis (TIRPOL_WITH_ARAVIS=OFF or not found): it cannot
// serve, so its constructor says so; the digital twin then falls back to its in-process camera.

#include "tirpol/acquisition/sim/fake_gige_server.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {

struct FakeGigECameraServer::Impl {};

FakeGigECameraServer::FakeGigECameraServer(FakeGigECameraOptions options) {
    fail("fake GigE Vision camera on {}: tirpol was built without Aravis (TIRPOL_WITH_ARAVIS)",
         options.interface);
}

FakeGigECameraServer::~FakeGigECameraServer() = default;

void FakeGigECameraServer::set_fill(FakeGigEFill) {}

std::string FakeGigECameraServer::device_id() const { return {}; }

const std::string& FakeGigECameraServer::interface() const {
    static const std::string none;
    return none;
}

}  // namespace tirpol::acquisition
