#pragma once
/// \file rng.h
/// Counter-based random numbers: every value is a pure function of (seed, pixel, sample,
/// dimension), so an image does not depend on the number of threads or on the order tiles are
/// rendered in (Salmon et al., "Parallel random numbers: as easy as 1, 2, 3", SC 2011 — the
/// counter-based idea; the mixing function is SplitMix64, Steele, Lea & Flood, OOPSLA 2014).

#include <cstdint>

namespace tirpol::simulation {

/// SplitMix64 finaliser: a bijective 64-bit mix with full avalanche.
constexpr std::uint64_t mix64(std::uint64_t z) {
    z += 0x9E3779B97F4A7C15ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

/// The random stream of one (seed, pixel, sample): uniform doubles in [0, 1) drawn by a counter.
class SampleStream {
public:
    SampleStream(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample)
        : m_key(mix64(mix64(mix64(seed) ^ pixel) ^ (sample * 0xD1B54A32D192ED03ULL))) {}

    /// Next uniform number in [0, 1) with 53 random bits.
    double next() {
        const std::uint64_t bits = mix64(m_key + 0x632BE59BD9B4E019ULL * ++m_counter);
        return static_cast<double>(bits >> 11) * 0x1.0p-53;
    }

private:
    std::uint64_t m_key;
    std::uint64_t m_counter = 0;
};

}  // namespace tirpol::simulation
