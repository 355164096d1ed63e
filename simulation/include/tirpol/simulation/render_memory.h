#pragma once
/// \file render_memory.h
/// What a render costs in memory, estimated before anything is allocated.

#include <cstdint>

namespace tirpol::simulation {

/// Bytes a render of width×height pixels at `spp` on `threads` workers needs at its peak: the image's
/// 17 float channels, the quicklook and EXR buffers of writing it (4 bytes a pixel), and each
/// worker's per-pixel sample strata (5 ints per sample). render() checks it against the memory
/// available (core check_memory_estimate) before allocating, and throws tirpol::Error with the estimate.
std::uint64_t render_memory_estimate_bytes(int width, int height, int spp, int threads);

}  // namespace tirpol::simulation
