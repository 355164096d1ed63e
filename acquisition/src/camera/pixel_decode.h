#pragma once
// Converts raw monochrome pixel rows into float counts. Layouts: 8-bit in one byte; 10/12/14/16-bit
// in a little-endian 16-bit container (GenICam PFNC Mono10/12/14/16 unpacked; V4L2 Y16, Y10, Y12
// are documented as little-endian 16-bit words in the kernel's pixel-format pages); 12-bit packed
// as PFNC Mono12p (LUCID's PolarizeMono12p): two pixels in three bytes, least-significant bits
// first — p0 = b0 | (b1 & 0x0F) << 8, p1 = b1 >> 4 | b2 << 4.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tirpol::acquisition {

/// Decodes `height` rows of `width` pixels of `bytes_per_pixel` (1 or 2) starting every
/// `stride_bytes`. `out` is resized to width × height. The caller has checked that the data is
/// large enough.
inline void decode_mono(const std::uint8_t* data, int width, int height, int bytes_per_pixel,
                        std::size_t stride_bytes, std::vector<float>& out) {
    const auto w = static_cast<std::size_t>(width);
    out.resize(w * static_cast<std::size_t>(height));
    for (std::size_t y = 0; y < static_cast<std::size_t>(height); ++y) {
        const std::uint8_t* row = data + y * stride_bytes;
        float* dst = out.data() + y * w;
        if (bytes_per_pixel == 1) {
            for (std::size_t x = 0; x < w; ++x) dst[x] = static_cast<float>(row[x]);
        } else {
            for (std::size_t x = 0; x < w; ++x) {
                const auto lo = static_cast<unsigned>(row[2 * x]);
                const auto hi = static_cast<unsigned>(row[2 * x + 1]);
                dst[x] = static_cast<float>(lo | (hi << 8u));
            }
        }
    }
}

/// Decodes PFNC Mono12p rows (see above) of `width` pixels starting every `stride_bytes`; an odd
/// width ends a row in the low 12 bits of a last pair. `out` is resized to width × height. The
/// caller has checked that the data holds (width · 12 + 7) / 8 bytes per row.
inline void decode_mono12p(const std::uint8_t* data, int width, int height,
                           std::size_t stride_bytes, std::vector<float>& out) {
    const auto w = static_cast<std::size_t>(width);
    out.resize(w * static_cast<std::size_t>(height));
    for (std::size_t y = 0; y < static_cast<std::size_t>(height); ++y) {
        const std::uint8_t* row = data + y * stride_bytes;
        float* dst = out.data() + y * w;
        for (std::size_t x = 0; x < w; ++x) {
            const std::uint8_t* pair = row + 3 * (x / 2);
            const unsigned value = x % 2 == 0
                                       ? pair[0] | (static_cast<unsigned>(pair[1] & 0x0Fu) << 8u)
                                       : (static_cast<unsigned>(pair[1]) >> 4u) |
                                             (static_cast<unsigned>(pair[2]) << 4u);
            dst[x] = static_cast<float>(value);
        }
    }
}

}  // namespace tirpol::acquisition
