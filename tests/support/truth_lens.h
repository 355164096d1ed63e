#pragma once
// The lens the geometric-calibration, camera-grid and geometry CLI tests use.

#include "tirpol/core/camera_model.h"

namespace tirpol::test {

/// The truth lens: a 640×512 uncooled core behind a ~13 mm f/1 lens, barrel distortion, principal
/// point off centre by (11.7, −8.8) px.
inline CameraModel truth_lens() {
    CameraModel m;
    m.width = 640;
    m.height = 512;
    m.fx = 762.0;
    m.fy = 765.5;
    m.cx = 331.7;
    m.cy = 247.2;
    m.distortion = {-0.32, 0.14, 0.0009, -0.0006, -0.035};
    return m;
}

}  // namespace tirpol::test
