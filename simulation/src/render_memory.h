#pragma once
/// \file render_memory.h
/// What a render costs in memory, estimated before anything is allocated.

#include <cstdint>

namespace tirpol::simulation {

/// Bytes a render of width×height pixels needs at its peak: the image's 18 float channels and the
/// quicklook and EXR buffers of writing it (4 bytes a pixel); nothing grows with spp or threads.
/// render() checks it against the memory available (core check_memory_estimate) before allocating,
/// and throws tirpol::Error with the estimate.
std::uint64_t render_memory_estimate_bytes(int width, int height);

}  // namespace tirpol::simulation
