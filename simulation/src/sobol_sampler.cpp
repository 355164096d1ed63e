#include "sobol_sampler.h"

namespace tirpol::simulation {

namespace {

std::uint32_t reverse_bits(std::uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
    return __builtin_bswap32(x);  // the byte order: one instruction for the last two swaps
}

/// All ones up to n − 1's highest bit (0 for n ≤ 1): the domain [0, mask] of the bijection that
/// permutation_element cycle-walks into [0, n).
std::uint32_t permutation_mask(std::uint32_t n) {
    if (n <= 1) return 0;
    std::uint32_t mask = n - 1;
    mask |= mask >> 1;
    mask |= mask >> 2;
    mask |= mask >> 4;
    mask |= mask >> 8;
    mask |= mask >> 16;
    return mask;
}

int permutation_half_bits(std::uint32_t mask) { return (32 - __builtin_clz(mask) + 1) / 2; }

/// permutation_element with n's mask and half its bit count given (n ≥ 2).
std::uint32_t permute(std::uint32_t index, std::uint32_t n, std::uint32_t mask, int half,
                      std::uint64_t key) {
    const auto k0 = static_cast<std::uint32_t>(key), k1 = static_cast<std::uint32_t>(key >> 32);
    // Each step is a bijection of [0, mask]: XOR or add a key, multiply by an odd constant (mod
    // 2^bits), XOR with itself shifted right. Repeating it until the value falls in [0, n) (cycle
    // walking) gives a bijection of [0, n); fewer than two rounds are needed on average since n >
    // mask / 2.
    std::uint32_t i = index;
    do {
        i ^= k0 & mask;
        i = (i * 0xe170893du) & mask;
        i ^= i >> half;
        i = (i + k1) & mask;
        i = (i * (0x0929eb3fu | (k0 >> 16) | 1u)) & mask;
        i ^= i >> 1;
        i ^= (k1 >> 16) & mask;
        i = (i * 0x6935fa69u) & mask;
        i ^= i >> half;
        i = (i * 0x74dcb303u) & mask;
    } while (i >= n);
    return i;
}

/// Burley's Laine–Karras-style hash on a bit-reversed fraction: bit j of the result is bit j of x
/// flipped by a function of the seed and bits below j (adding, and x ^= x·c with c even, never
/// carry information downward). Bits below j of the reversed value are the digits above j's of the
/// fraction.
std::uint32_t laine_karras_permutation(std::uint32_t x, std::uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

constexpr double kTwoToMinus32 = 0x1.0p-32;

/// Joe & Kuo's direction numbers (new-joe-kuo-6.21201) of Sobol dimensions 2–7 (1-based, as in
/// their file; dimension 1 is van der Corput's): degree s of the primitive polynomial, its inner
/// coefficients a (bits, highest degree first) and the initial odd m_1 … m_s.
struct JoeKuoDimension {
    int s;
    std::uint32_t a;
    std::array<std::uint32_t, 4> m;
};
constexpr std::array<JoeKuoDimension, kSobolDimensions - 1> kJoeKuo = {{{1, 0, {1}},
                                                                        {2, 1, {1, 3}},
                                                                        {3, 1, {1, 3, 1}},
                                                                        {3, 2, {1, 1, 1}},
                                                                        {4, 1, {1, 1, 3, 3}},
                                                                        {4, 4, {1, 3, 5, 13}}}};

/// Each dimension's 32 direction numbers v_k (the generator matrix's columns, as fractions),
/// bit-reversed: the Owen scramble works on reversed fractions, and reversal is linear over XOR, so
/// a point's reversed coordinate is the XOR of the reversed columns its index selects. Bratley &
/// Fox's recurrence (ACM TOMS 14(1), 1988, algorithm 659): v_k = m_k/2^k for k ≤ s, then
/// v_k = v_(k−s) ⊕ v_(k−s)/2^s ⊕ a_1·v_(k−1) ⊕ … ⊕ a_(s−1)·v_(k−s+1).
constexpr std::array<std::array<std::uint32_t, 32>, kSobolDimensions> reversed_directions() {
    std::array<std::array<std::uint32_t, 32>, kSobolDimensions> table{};
    const auto reverse = [](std::uint32_t x) {
        std::uint32_t r = 0;
        for (int b = 0; b < 32; ++b) r |= ((x >> b) & 1u) << (31 - b);
        return r;
    };
    for (int k = 0; k < 32; ++k) table[0][static_cast<std::size_t>(k)] = 1u << k;
    for (int d = 1; d < kSobolDimensions; ++d) {
        const JoeKuoDimension& jk = kJoeKuo[static_cast<std::size_t>(d - 1)];
        std::array<std::uint32_t, 32> v{};  // v[k] is v_(k+1)
        for (int k = 0; k < 32; ++k) {
            const auto ku = static_cast<std::size_t>(k);
            if (k < jk.s) {
                v[ku] = jk.m[ku] << (31 - k);
                continue;
            }
            const std::uint32_t back = v[static_cast<std::size_t>(k - jk.s)];
            v[ku] = back ^ (back >> jk.s);
            for (int j = 1; j < jk.s; ++j)
                if (((jk.a >> (jk.s - 1 - j)) & 1u) != 0)
                    v[ku] ^= v[static_cast<std::size_t>(k - j)];
        }
        for (int k = 0; k < 32; ++k)
            table[static_cast<std::size_t>(d)][static_cast<std::size_t>(k)] =
                reverse(v[static_cast<std::size_t>(k)]);
    }
    return table;
}
constexpr auto kReversedDirections = reversed_directions();

/// Sobol coordinate `dimension` of point `index`, bit-reversed.
std::uint32_t sobol_reversed(std::uint32_t index, int dimension) {
    if (dimension == 0) return index;  // van der Corput: the reversal of its reversal
    const auto& columns = kReversedDirections[static_cast<std::size_t>(dimension)];
    std::uint32_t x = 0;
    for (std::uint32_t rest = index; rest != 0; rest &= rest - 1)
        x ^= columns[static_cast<std::size_t>(__builtin_ctz(rest))];
    return x;
}

}  // namespace

std::uint32_t sobol_coordinate(std::uint32_t index, int dimension) {
    return reverse_bits(sobol_reversed(index, dimension));
}

std::uint32_t owen_scramble(std::uint32_t fraction, std::uint32_t seed) {
    return reverse_bits(laine_karras_permutation(reverse_bits(fraction), seed));
}

std::uint32_t permutation_element(std::uint32_t index, std::uint32_t n, std::uint64_t key) {
    if (n <= 1) return 0;
    const std::uint32_t mask = permutation_mask(n);
    return permute(index, n, mask, permutation_half_bits(mask), key);
}

ReplicateSampler::ReplicateSampler(std::uint64_t seed, std::uint64_t pixel, std::uint32_t replicate,
                                   std::uint32_t points)
    : m_key(mix64(mix64(mix64(seed ^ 0x5EEDC0DE50B01ULL) ^ pixel) ^
                  (replicate * 0x9FB21C651E98DF25ULL))),
      m_points(points),
      m_mask(permutation_mask(points)),
      m_half_bits(m_mask != 0 ? permutation_half_bits(m_mask) : 0) {
    // The prefix's keys: one permutation for all its numbers, a scramble per number.
    m_prefix_permutation = mix64(m_key ^ 0x9E3779B97F4A7C15ULL);
    for (std::size_t i = 0; i < m_prefix_scrambles.size(); i += 2) {
        const std::uint64_t key = mix64(m_prefix_permutation ^ (i + 1) * 0xBF58476D1CE4E5B9ULL);
        m_prefix_scrambles[i] = static_cast<std::uint32_t>(key);
        if (i + 1 < m_prefix_scrambles.size())
            m_prefix_scrambles[i + 1] = static_cast<std::uint32_t>(key >> 32);
    }
}

std::uint32_t ReplicateSampler::prefix_point(std::uint32_t index) const {
    return permuted(index, m_prefix_permutation);
}

double ReplicateSampler::prefix(std::uint32_t point, int number) const {
    const auto n = static_cast<std::size_t>(number);
    return reverse_bits(laine_karras_permutation(sobol_reversed(point, kPrefixSobolDimensions[n]),
                                                 m_prefix_scrambles[n])) *
           kTwoToMinus32;
}

ReplicateSampler::SlotKeys ReplicateSampler::slot_keys(std::uint32_t slot) const {
    const auto hash = [this](std::uint32_t s) {
        const std::uint64_t key = mix64(m_key ^ (s * 0xD1B54A32D192ED03ULL));
        return SlotKeys{key, mix64(key)};
    };
    // With one point per replicate every slot is asked for once: keeping its keys would only cost.
    if (m_points == 1 || slot >= kKeptSlots) return hash(slot);
    if ((m_kept >> slot & 1u) == 0) {
        m_slot_keys[slot] = hash(slot);
        m_kept |= 1u << slot;
    }
    return m_slot_keys[slot];
}

std::uint32_t ReplicateSampler::permuted(std::uint32_t index, std::uint64_t permutation_key) const {
    return m_mask == 0 ? 0 : permute(index, m_points, m_mask, m_half_bits, permutation_key);
}

std::array<double, 2> ReplicateSampler::pair(std::uint32_t index, std::uint32_t slot) const {
    const SlotKeys keys = slot_keys(slot);
    const std::uint32_t j = permuted(index, keys.permutation);
    // van der Corput's radical inverse is the bit reversal of j: scrambling it in the reversed
    // domain needs no reversal of the input.
    const std::uint32_t x =
        reverse_bits(laine_karras_permutation(j, static_cast<std::uint32_t>(keys.scramble)));
    const std::uint32_t y = reverse_bits(laine_karras_permutation(
        sobol_reversed(j, 1), static_cast<std::uint32_t>(keys.scramble >> 32)));
    return {x * kTwoToMinus32, y * kTwoToMinus32};
}

double ReplicateSampler::single(std::uint32_t index, std::uint32_t slot) const {
    const SlotKeys keys = slot_keys(slot);
    const std::uint32_t j = permuted(index, keys.permutation);
    return reverse_bits(laine_karras_permutation(j, static_cast<std::uint32_t>(keys.scramble))) *
           kTwoToMinus32;
}

}  // namespace tirpol::simulation
