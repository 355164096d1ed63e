#pragma once
// Latin-hypercube design in the unit cube (McKay, Beckman & Conover, Technometrics 21, 239 (1979)):
// each of the `dimensions` axes is cut into `points` equal strata and every stratum holds exactly
// one point, so even a few starts spread over every parameter's whole range.

#include <cstdint>
#include <vector>

namespace tirpol::fitting::detail {

/// `points` points in [0, 1)^dimensions from a fixed seed (same output on every platform: the
/// generator is std::mt19937_64 and the mapping to doubles is written out, not a std distribution).
std::vector<std::vector<double>> latin_hypercube(std::size_t points, std::size_t dimensions,
                                                 std::uint64_t seed);

}  // namespace tirpol::fitting::detail
