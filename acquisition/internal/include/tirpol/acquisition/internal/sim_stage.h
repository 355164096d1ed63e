#pragma once
/// \file sim_stage.h
/// An in-process simulated rotation stage (`sim://`): exact positions, optional move speed so a
/// move takes |Δθ|/speed of wall time (the angle turns with time meanwhile), optional injected
/// failure on a given move.

#include <functional>
#include <memory>
#include <optional>

#include "tirpol/acquisition/stage.h"

namespace tirpol::acquisition {

struct SimulatedStageOptions {
    double deg_per_s = 0.0;  ///< 0: moves complete at once
    double counts_per_degree = 409600.0 / 3.0;
    double start_angle_deg = 0.0;     ///< where the stage sits before homing
    std::optional<int> fail_on_move;  ///< 1-based absolute move that returns DeviceFault
};

std::unique_ptr<Stage> make_simulated_stage(std::string uri,
                                            const SimulatedStageOptions& options = {});

/// The physical angle of a stage made by make_simulated_stage, time-true during a move (it turns at
/// deg_per_s) and safe to call from any thread: the angle source of a free-running simulated
/// camera. Throws tirpol::Error for another kind of stage. The stage must outlive the function.
std::function<double()> simulated_stage_angle_source(Stage& stage);

}  // namespace tirpol::acquisition
