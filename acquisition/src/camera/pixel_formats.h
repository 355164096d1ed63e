#pragma once
// The GenICam pixel formats tirpol reads: monochrome, and the raw mosaic of a microgrid
// (division-of-focal-plane) polarization sensor, which is monochrome data whose 2×2 cells hold four
// analyzer angles.
//
// Codes: PFNC (GenICam Pixel Format Naming Convention 2.x; bits 16–23 are the bits a pixel
// occupies). The polarized formats are LUCID Vision Labs' custom codes (bit 31 set, as PFNC
// reserves for vendors) from the PFNC header of LUCID's Arena SDK (`LUCID_PolarizeMono8
// 0x81080001`, ...), the names its Phoenix/Triton/Atlas polarization cameras (Sony IMX250MZR)
// list under PixelFormat. PolarizeMono12p packs as PFNC Mono12p (two pixels in three bytes,
// least-significant bits first); PolarizeMono12 and PolarizeMono16 are little-endian 16-bit words,
// as Mono12/Mono16.

#include <array>
#include <cstdint>
#include <string_view>

namespace tirpol::acquisition {

struct GenICamPixelFormat {
    std::string_view name;
    std::uint32_t pfnc_code = 0;
    int significant_bits = 0;  ///< values are in [0, 2^bits − 1]
    int stored_bits = 0;       ///< bits a pixel occupies in the buffer: 8, 12 (packed) or 16
    bool polarized = false;    ///< a microgrid mosaic (the sensor's 2×2 analyzer pattern)
};

inline constexpr std::array kGenICamPixelFormats = {
    GenICamPixelFormat{"Mono8", 0x01080001u, 8, 8, false},
    GenICamPixelFormat{"Mono10", 0x01100003u, 10, 16, false},
    GenICamPixelFormat{"Mono12", 0x01100005u, 12, 16, false},
    GenICamPixelFormat{"Mono14", 0x01100025u, 14, 16, false},
    GenICamPixelFormat{"Mono16", 0x01100007u, 16, 16, false},
    GenICamPixelFormat{"PolarizeMono8", 0x81080001u, 8, 8, true},
    GenICamPixelFormat{"PolarizeMono12", 0x81100008u, 12, 16, true},
    GenICamPixelFormat{"PolarizeMono12p", 0x810C0047u, 12, 12, true},
    GenICamPixelFormat{"PolarizeMono16", 0x81100007u, 16, 16, true},
};

/// The format of this name, or nullptr when tirpol does not read it.
inline const GenICamPixelFormat* find_pixel_format(std::string_view name) {
    for (const auto& f : kGenICamPixelFormats)
        if (f.name == name) return &f;
    return nullptr;
}

/// The format of this PFNC code, or nullptr when tirpol does not read it.
inline const GenICamPixelFormat* find_pixel_format(std::uint32_t pfnc_code) {
    for (const auto& f : kGenICamPixelFormats)
        if (f.pfnc_code == pfnc_code) return &f;
    return nullptr;
}

/// Bytes one row of `width` pixels occupies (packed 12-bit: 3 bytes per 2 pixels, rounded up).
inline std::size_t row_bytes(const GenICamPixelFormat& format, int width) {
    return (static_cast<std::size_t>(width) * static_cast<std::size_t>(format.stored_bits) + 7) / 8;
}

/// The sensor layout of the polarized formats above (Sony IMX250MZR, as LUCID documents it for its
/// polarization cameras): analyzer angles at cell positions (0,0), (0,1), (1,0), (1,1) of
/// (y mod 2, x mod 2), degrees.
inline constexpr std::array<double, 4> kSonyPolarizedLayoutDeg{90.0, 45.0, 135.0, 0.0};

}  // namespace tirpol::acquisition
