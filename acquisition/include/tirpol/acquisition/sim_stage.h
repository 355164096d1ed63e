#pragma once
/// \file sim_stage.h
/// An in-process simulated rotation stage (`sim://`): exact positions, optional move speed so a
/// move takes |Δθ|/speed of wall time, optional injected failure on a given move.

#include <memory>
#include <optional>

#include "tirpol/acquisition/stage.h"

namespace tirpol::acquisition {

struct SimulatedStageOptions {
    double deg_per_s = 0.0;                 ///< 0: moves complete at once
    double counts_per_degree = 409600.0 / 3.0;
    double start_angle_deg = 0.0;           ///< where the stage sits before homing
    std::optional<int> fail_on_move;        ///< 1-based absolute move that returns DeviceFault
};

std::unique_ptr<Stage> make_simulated_stage(std::string uri, const SimulatedStageOptions& options = {});

}  // namespace tirpol::acquisition
