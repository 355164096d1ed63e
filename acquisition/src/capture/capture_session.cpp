#include "tirpol/acquisition/capture.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {

SessionWriter open_capture_session(const std::filesystem::path& dir, const CameraInfo& camera,
                                   const StageInfo& stage, const CapturePlan& plan, bool resume,
                                   const BlackbodyInfo* blackbody) {
    if (!resume)
        return SessionWriter::create(dir, new_session_manifest(camera, stage, plan, blackbody));
    if (!std::filesystem::exists(dir / kSessionManifestName))
        fail("{}: no session to resume here (no {}); leave out --resume to start one", dir.string(),
             kSessionManifestName);
    SessionWriter session = SessionWriter::resume(dir);
    check_resumable(session.manifest(), camera, plan);
    return session;
}

}  // namespace tirpol::acquisition
