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

/// The second coordinate of sobol_02_point, bit-reversed: the Owen scramble works on reversed
/// fractions, and bit reversal is linear over XOR, so the reversed generator columns (1, 3, 5, 15,
/// 17, …: each the previous XOR itself shifted left by one) give it without the two reversals that
/// owen_scramble(sobol_02_point(index)[1], seed) spends.
std::uint32_t sobol_second_reversed(std::uint32_t index) {
    std::uint32_t second = 0;
    for (std::uint32_t rest = index, column = 1u; rest != 0; rest >>= 1, column ^= column << 1)
        if ((rest & 1u) != 0) second ^= column;
    return second;
}

}  // namespace

std::array<std::uint32_t, 2> sobol_02_point(std::uint32_t index) {
    // Second coordinate: generator matrix = upper-triangular Pascal matrix mod 2, whose columns are
    // 1/2, 3/4, 5/8, 15/16, 17/32, … (each is the previous XOR itself shifted right by one).
    std::uint32_t second = 0;
    for (std::uint32_t rest = index, column = 0x80000000u; rest != 0;
         rest >>= 1, column ^= column >> 1)
        if ((rest & 1u) != 0) second ^= column;
    return {reverse_bits(index), second};
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
      m_half_bits(m_mask != 0 ? permutation_half_bits(m_mask) : 0) {}

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
        sobol_second_reversed(j), static_cast<std::uint32_t>(keys.scramble >> 32)));
    return {x * kTwoToMinus32, y * kTwoToMinus32};
}

double ReplicateSampler::single(std::uint32_t index, std::uint32_t slot) const {
    const SlotKeys keys = slot_keys(slot);
    const std::uint32_t j = permuted(index, keys.permutation);
    return reverse_bits(laine_karras_permutation(j, static_cast<std::uint32_t>(keys.scramble))) *
           kTwoToMinus32;
}

}  // namespace tirpol::simulation
