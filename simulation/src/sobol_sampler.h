#pragma once
/// \file sobol_sampler.h
/// The renderer's random numbers: Owen-scrambled Sobol points with independent randomised
/// replicates per pixel, one Sobol sequence for the path's first dimensions and padded
/// (0,2)-sequences after.
///
/// Prefix: the numbers that shape most of a pixel's value — the first bounce's pBRDF pair, the
/// wavelength, the sub-pixel position and the second bounce's pBRDF pair — are consecutive
/// coordinates of ONE point of the Sobol sequence (Sobol 1967; direction numbers of Joe & Kuo,
/// "Constructing Sobol sequences with better two-dimensional projections", SIAM J. Sci. Comput.
/// 30(5), 2008, file new-joe-kuo-6.21201), so their joint distribution is stratified and not only
/// each pair's: a rough sphere whose pixel position and reflected direction together pick walls of
/// different temperatures converges faster than with independently paired slots. Each coordinate
/// is Owen-scrambled with its own hashed seed and the replicate's point order is shuffled by one
/// permutation shared by all prefix coordinates (a permutation per coordinate would re-pair them
/// at random and lose the joint stratification). kPrefixSobolDimensions says which Sobol dimension
/// each number takes: the first bounce gets dimensions 1–2, a (0,2)-sequence, whose 2^m-point
/// prefixes are (0,m,2)-nets.
///
/// Padding (Kollig & Keller, "Efficient multidimensional sampling", Eurographics 2002; pbrt-v4's
/// PaddedSobolSampler, Mitsuba 3's `ldsampler`): the numbers after the prefix — deeper bounces'
/// pBRDF pairs and the Russian-roulette numbers — are grouped into slots, each taking the first n
/// points of the (0,2)-sequence with its own Owen scrambles and its own random permutation of the
/// sample index, so every slot stays a net and slots are independent.
///
/// Owen scrambling is hashed (Laine & Karras, "Stratified sampling for stochastic transparency",
/// EGSR 2011; constants of Burley, "Practical hash-based Owen scrambling", JCGT 9(4), 2020); the
/// index permutation is a keyed bijection of [0, 2^b) cycle-walked into [0, n) (after Kensler,
/// "Correlated multi-jittered sampling", Pixar TM 13-01, 2013).
///
/// Replicates (L'Ecuyer & Lemieux, "Recent advances in randomized quasi-Monte Carlo methods", 2002;
/// Owen, "Monte Carlo theory, methods and examples", ch. 17): a pixel's samples are R replicates of
/// n points, each with its own scrambles and permutations, so the replicate means are i.i.d. and
/// Σ_r (m_r − m̄)² / (R(R − 1)) is an exactly unbiased estimate of the variance of their average.
///
/// Every value is a pure function of (seed, pixel, replicate, sample index, dimension or slot):
/// images do not depend on threads or tiling, and nothing is stored per sample (memory does not
/// grow with spp).

#include <array>
#include <cstdint>
#include <optional>

#include "rng.h"

namespace tirpol::simulation {

/// Bounces whose BSDF pair and roulette number come from the scrambled sequences; deeper bounces
/// (rare: Russian roulette ends most paths by then) draw from the pixel sample's SampleStream
/// instead.
inline constexpr int kSobolBounces = 8;

/// Bounces whose pBRDF pair is in the prefix (the first bounce sees what the pixel sees, the second
/// what lights it: both shape the emission scene's sphere pixels).
inline constexpr int kPrefixBounces = 2;
/// The prefix's numbers: sub-pixel x and y, the wavelength, then each prefix bounce's pBRDF pair.
inline constexpr int kPrefixSize = 3 + 2 * kPrefixBounces;
/// Sobol dimensions the prefix may use (0: van der Corput), Joe & Kuo's first seven.
inline constexpr int kSobolDimensions = 7;
/// The Sobol dimension (0-based) of each prefix number. The first bounce's pair takes dimensions
/// 0–1, the only (0,2)-sequence; the sub-pixel and second bounce's pairs take the pairs of
/// dimensions 3–6 whose 2^m-point projections have t ≤ 2 up to m = 8 (dimensions 4 and 6, 3 and
/// 5); the wavelength takes dimension 2, with which 0–1 form a (1,3)-sequence.
inline constexpr std::array<int, kPrefixSize> kPrefixSobolDimensions = {4, 6, 2, 0, 1, 3, 5};

/// Coordinate `dimension` (0 ≤ dimension < kSobolDimensions; 0 is van der Corput's radical
/// inverse, 1 the Pascal matrix, 2 on Joe & Kuo's) of Sobol point `index`, as a 32-bit fraction.
/// Unscrambled.
std::uint32_t sobol_coordinate(std::uint32_t index, int dimension);

/// Hashed nested uniform (Owen) scramble of a 32-bit fraction: each digit is flipped by a function
/// of `seed` and the digits above it, so nets stay nets and every point becomes uniform in [0, 1).
std::uint32_t owen_scramble(std::uint32_t fraction, std::uint32_t seed);

/// A pseudo-random permutation of [0, n) (n ≥ 1) keyed by `key`: element `index` of it.
std::uint32_t permutation_element(std::uint32_t index, std::uint32_t n, std::uint64_t key);

/// The numbers of one replicate of one pixel: `points` samples, each a scrambled Sobol prefix point
/// and a padded scrambled (0,2)-sequence point per slot. Cheap to construct (its key and the
/// prefix's scramble keys; each slot's permutation and scramble keys are hashed on the slot's first
/// use and kept for the replicate's other samples). One object per thread: the kept keys are
/// written by the const accessors.
class ReplicateSampler {
public:
    /// `points` ≥ 1 samples in this replicate; (seed, pixel, replicate) pick its independent
    /// scrambles.
    ReplicateSampler(std::uint64_t seed, std::uint64_t pixel, std::uint32_t replicate,
                     std::uint32_t points);

    /// The Sobol point (< points) that sample `index` (< points) takes for every prefix number.
    std::uint32_t prefix_point(std::uint32_t index) const;
    /// Prefix number `number` (< kPrefixSize) of the replicate's Sobol point `point`, scrambled,
    /// in [0, 1).
    double prefix(std::uint32_t point, int number) const;

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
    /// Slots whose keys are kept: the scrambled bounces' pairs and roulette numbers.
    static constexpr std::uint32_t kKeptSlots = 2 * kSobolBounces;

    SlotKeys slot_keys(std::uint32_t slot) const;
    std::uint32_t permuted(std::uint32_t index, std::uint64_t permutation_key) const;

    std::uint64_t m_key;
    std::uint32_t m_points;
    std::uint32_t m_mask = 0;  ///< all ones up to points − 1's highest bit (permutation_element)
    int m_half_bits = 0;
    std::uint64_t m_prefix_permutation = 0;
    std::array<std::uint32_t, kPrefixSize> m_prefix_scrambles{};
    mutable std::uint32_t m_kept = 0;  ///< bit s: m_slot_keys[s] holds slot s's keys
    mutable std::array<SlotKeys, kKeptSlots> m_slot_keys;
};

/// The random numbers of one path: the replicate's prefix point and padded slots for the bounces
/// they cover, the sample's counter-based stream (rng.h) beyond kSobolBounces. The stream is keyed
/// on its first use only: most paths end before kSobolBounces, and its key costs three hashes.
class PathSampler {
public:
    /// Sample `index` of `replicate`; the fallback stream is SampleStream(seed, pixel,
    /// stream_sample), this sample's own.
    PathSampler(const ReplicateSampler& replicate, std::uint32_t index, std::uint64_t seed,
                std::uint64_t pixel, std::uint64_t stream_sample)
        : m_replicate(replicate),
          m_index(index),
          m_point(replicate.prefix_point(index)),
          m_seed(seed),
          m_pixel(pixel),
          m_stream_sample(stream_sample) {}

    /// Sub-pixel position, each in [0, 1).
    std::array<double, 2> subpixel() const {
        return {m_replicate.prefix(m_point, kSubpixelX), m_replicate.prefix(m_point, kSubpixelY)};
    }
    /// Picks the wavelength node (inverse CDF of the band weights).
    double wavelength() const { return m_replicate.prefix(m_point, kWavelength); }
    /// The BSDF's two numbers at `bounce` (0: the camera's first hit).
    std::array<double, 2> scatter(int bounce) {
        if (bounce < kPrefixBounces)
            return {m_replicate.prefix(m_point, kFirstBounce + 2 * bounce),
                    m_replicate.prefix(m_point, kFirstBounce + 2 * bounce + 1)};
        if (bounce >= kSobolBounces) {
            SampleStream& stream = fallback();
            const double u1 = stream.next();
            return {u1, stream.next()};
        }
        return m_replicate.pair(m_index, 2 * static_cast<std::uint32_t>(bounce));
    }
    /// The Russian-roulette number at `bounce`.
    double roulette(int bounce) {
        if (bounce >= kSobolBounces) return fallback().next();
        return m_replicate.single(m_index, 2 * static_cast<std::uint32_t>(bounce) + 1);
    }

private:
    /// The prefix's numbers (kPrefixSobolDimensions).
    static constexpr int kSubpixelX = 0, kSubpixelY = 1, kWavelength = 2, kFirstBounce = 3;

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
    std::uint32_t m_index, m_point;
    std::uint64_t m_seed, m_pixel, m_stream_sample;
    std::optional<SampleStream> m_fallback;
};

}  // namespace tirpol::simulation
