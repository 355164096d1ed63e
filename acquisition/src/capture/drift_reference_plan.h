#pragma once
/// \file drift_reference_plan.h
/// The capture plan's drift references (capture_plan.h): `scene_reference` (an in-scene reference
/// blackbody region) and `shutter_interleave` (shutter records between the scene records). The
/// session stores them in its plan JSON, where calibration's offset_drift.h reads them.

#include "tirpol/acquisition/capture_plan.h"

namespace tirpol::acquisition::detail {

/// Parses both keys of `root` into `plan`; throws tirpol::Error naming the file, line and field.
void parse_drift_references(const ConfigNode& root, CapturePlan& plan);

/// Adds them to the plan JSON when given (a plan without them keeps the JSON of earlier versions).
void drift_references_json(const CapturePlan& plan, nlohmann::json& out);

/// The `index`-th interleaved shutter step, at the polarizer angle of its neighbouring scene step.
CaptureStep interleaved_shutter_step(const ShutterInterleaveSpec& spec, int index,
                                     double angle_deg);

}  // namespace tirpol::acquisition::detail
