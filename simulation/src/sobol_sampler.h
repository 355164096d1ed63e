#pragma once
/// \file sobol_sampler.h
/// The renderer's random numbers: a padded, Owen-scrambled (0,2)-sequence sampler with independent
/// randomised replicates per pixel.
///
/// Construction (Kollig & Keller, "Efficient multidimensional sampling", Eurographics 2002; the
/// same as pbrt-v4's PaddedSobolSampler and Mitsuba 3's `ldsampler`): the path's random numbers are
/// grouped into dimension slots (sub-pixel position, wavelength, and per bounce the BSDF pair and
/// the Russian- roulette number). Each slot takes the first n points of the (0,2)-sequence formed
/// by the first two Sobol dimensions (van der Corput and its companion, generator matrices I and
/// the Pascal matrix mod 2), Owen-scrambled independently per coordinate, with the sample index
/// randomly permuted per slot
/// ("padding": the pairing of one slot's points with another's is random, so every slot stays a net
/// and slots are independent). Owen scrambling is hashed (Laine & Karras, "Stratified sampling for
/// stochastic transparency", EGSR 2011; constants of Burley, "Practical hash-based Owen
/// scrambling", JCGT 9(4), 2020); the index permutation is a keyed bijection of [0, 2^b)
/// cycle-walked into [0, n) (after Kensler, "Correlated multi-jittered sampling", Pixar TM 13-01,
/// 2013). No tables.
///
/// Replicates (L'Ecuyer & Lemieux, "Recent advances in randomized quasi-Monte Carlo methods", 2002;
/// Owen, "Monte Carlo theory, methods and examples", ch. 17): a pixel's samples are R replicates of
/// n points, each with its own scrambles and permutations, so the replicate means are i.i.d. and
/// Σ_r (m_r − m̄)² / (R(R − 1)) is an exactly unbiased estimate of the variance of their average.
///
/// Every value is a pure function of (seed, pixel, replicate, sample index, slot): images do not
/// depend on threads or tiling, and nothing is stored per sample (memory does not grow with spp).

#include <array>
#include <cstdint>
#include <optional>

#include "rng.h"

namespace tirpol::simulation {

/// Bounces whose BSDF pair and roulette number come from the scrambled sequence; deeper bounces
/// (rare: Russian roulette ends most paths by then) draw from the pixel sample's SampleStream
/// instead.
inline constexpr int kSobolBounces = 8;

/// The first n points of the two-dimensional (0,2)-sequence, each coordinate as a 32-bit fraction:
/// `index`'s van der Corput radical inverse and the second Sobol dimension. Unscrambled.
std::array<std::uint32_t, 2> sobol_02_point(std::uint32_t index);

/// Hashed nested uniform (Owen) scramble of a 32-bit fraction: each digit is flipped by a function
/// of `seed` and the digits above it, so nets stay nets and every point becomes uniform in [0, 1).
std::uint32_t owen_scramble(std::uint32_t fraction, std::uint32_t seed);

/// A pseudo-random permutation of [0, n) (n ≥ 1) keyed by `key`: element `index` of it.
std::uint32_t permutation_element(std::uint32_t index, std::uint32_t n, std::uint64_t key);

/// The numbers of one replicate of one pixel: `points` samples, each a padded scrambled
/// (0,2)-sequence point per slot. Cheap to construct (its key; each slot's permutation and scramble
/// keys are hashed on the slot's first use and kept for the replicate's other samples). One object
/// per thread: the kept keys are written by the const accessors.
class ReplicateSampler {
public:
    /// `points` ≥ 1 samples in this replicate; (seed, pixel, replicate) pick its independent
    /// scrambles.
    ReplicateSampler(std::uint64_t seed, std::uint64_t pixel, std::uint32_t replicate,
                     std::uint32_t points);

    /// Slot `slot`'s two numbers in [0, 1) for sample `index` (< points).
    std::array<double, 2> pair(std::uint32_t index, std::uint32_t slot) const;
    /// Slot `slot`'s one number in [0, 1) for sample `index`: the scrambled van der Corput
    /// coordinate.
    double single(std::uint32_t index, std::uint32_t slot) const;

    std::uint32_t points() const { return m_points; }

private:
    /// A slot's keys: of its index permutation and of its Owen scrambles (two 32-bit halves).
    struct SlotKeys {
        std::uint64_t permutation, scramble;
    };
    /// Slots whose keys are kept: the sub-pixel, wavelength and scrambled bounces' slots.
    static constexpr std::uint32_t kKeptSlots = 2 + 2 * kSobolBounces;

    SlotKeys slot_keys(std::uint32_t slot) const;
    std::uint32_t permuted(std::uint32_t index, std::uint64_t permutation_key) const;

    std::uint64_t m_key;
    std::uint32_t m_points;
    std::uint32_t m_mask = 0;  ///< all ones up to points − 1's highest bit (permutation_element)
    int m_half_bits = 0;
    mutable std::uint32_t m_kept = 0;  ///< bit s: m_slot_keys[s] holds slot s's keys
    mutable std::array<SlotKeys, kKeptSlots> m_slot_keys;
};

/// The random numbers of one path: the replicate's scrambled sequence for the slots it covers, the
/// sample's counter-based stream (rng.h) beyond kSobolBounces. The stream is keyed on its first use
/// only: most paths end before kSobolBounces, and its key costs three hashes.
class PathSampler {
public:
    /// Sample `index` of `replicate`; the fallback stream is SampleStream(seed, pixel,
    /// stream_sample), this sample's own.
    PathSampler(const ReplicateSampler& replicate, std::uint32_t index, std::uint64_t seed,
                std::uint64_t pixel, std::uint64_t stream_sample)
        : m_replicate(replicate),
          m_index(index),
          m_seed(seed),
          m_pixel(pixel),
          m_stream_sample(stream_sample) {}

    /// Sub-pixel position, each in [0, 1).
    std::array<double, 2> subpixel() const { return m_replicate.pair(m_index, kSubpixelSlot); }
    /// Picks the wavelength node (inverse CDF of the band weights).
    double wavelength() const { return m_replicate.single(m_index, kWavelengthSlot); }
    /// The BSDF's two numbers at `bounce` (0: the camera's first hit).
    std::array<double, 2> scatter(int bounce) {
        if (bounce >= kSobolBounces) {
            SampleStream& stream = fallback();
            const double u1 = stream.next();
            return {u1, stream.next()};
        }
        return m_replicate.pair(m_index, kFirstBounceSlot + 2 * static_cast<std::uint32_t>(bounce));
    }
    /// The Russian-roulette number at `bounce`.
    double roulette(int bounce) {
        if (bounce >= kSobolBounces) return fallback().next();
        return m_replicate.single(m_index,
                                  kFirstBounceSlot + 2 * static_cast<std::uint32_t>(bounce) + 1);
    }

private:
    static constexpr std::uint32_t kSubpixelSlot = 0, kWavelengthSlot = 1, kFirstBounceSlot = 2;

    SampleStream& fallback() {
        if (!m_fallback) key_fallback();
        return *m_fallback;
    }
    /// Out of line and cold: inlined, the compiler hoisted the key's pure arithmetic out of the
    /// bounce loop and computed it for every path.
    [[gnu::noinline, gnu::cold]] void key_fallback() {
        m_fallback.emplace(m_seed, m_pixel, m_stream_sample);
    }

    const ReplicateSampler& m_replicate;
    std::uint32_t m_index;
    std::uint64_t m_seed, m_pixel, m_stream_sample;
    std::optional<SampleStream> m_fallback;
};

}  // namespace tirpol::simulation
