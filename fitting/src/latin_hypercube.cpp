#include "latin_hypercube.h"

#include <numeric>
#include <random>

namespace tirpol::fitting::detail {

std::vector<std::vector<double>> latin_hypercube(std::size_t points, std::size_t dimensions,
                                                 std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    auto uniform = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
    std::vector<std::vector<double>> out(points, std::vector<double>(dimensions));
    std::vector<std::size_t> strata(points);
    for (std::size_t d = 0; d < dimensions; ++d) {
        std::iota(strata.begin(), strata.end(), std::size_t{0});
        // Fisher–Yates with the explicit uniform above (std::shuffle's algorithm is unspecified).
        for (std::size_t i = points; i > 1; --i) {
            const auto j = static_cast<std::size_t>(uniform() * static_cast<double>(i));
            std::swap(strata[i - 1], strata[j]);
        }
        for (std::size_t p = 0; p < points; ++p)
            out[p][d] = (static_cast<double>(strata[p]) + uniform()) / static_cast<double>(points);
    }
    return out;
}

}  // namespace tirpol::fitting::detail
