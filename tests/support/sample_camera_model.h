#pragma once
// A 640×512 camera model whose intrinsics have exact binary fractions (so a YAML round trip and
// OpenCV's projection compare to the last bit); tests add distortion and metadata as they need.

#include "tirpol/core/camera_model.h"

namespace tirpol::test {

/// fx 760.25, fy 762.5, principal point (330.125, 249.75), no distortion.
inline CameraModel sample_camera_model() {
    CameraModel m;
    m.width = 640;
    m.height = 512;
    m.fx = 760.25;
    m.fy = 762.5;
    m.cx = 330.125;
    m.cy = 249.75;
    return m;
}

}  // namespace tirpol::test
