#pragma once
// Decodes the live view's wire format (live/src/display_frame.h) the way live.js
// does, so tests can check what a page receives.

#include <cstdint>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tirpol::test {

struct DecodedImage {
    nlohmann::json header;
    std::vector<std::vector<std::uint16_t>> codes;  ///< per channel

    /// Value of pixel i of channel c; NaN for the codes "none", "dead" and "saturated".
    double value(std::size_t c, std::size_t i) const {
        const std::uint16_t q = codes[c][i];
        if (q == 0 || q == 1 || q == 65535) return std::numeric_limits<double>::quiet_NaN();
        const double lo = header["channels"][c]["min"], hi = header["channels"][c]["max"];
        return lo + (q - 2) * (hi - lo) / 65532.0;
    }
    /// The quantisation step of channel c (the largest error of value()).
    double step(std::size_t c) const {
        const double lo = header["channels"][c]["min"], hi = header["channels"][c]["max"];
        return (hi - lo) / 65532.0;
    }
};

inline DecodedImage decode_live_image(const std::string& bytes) {
    DecodedImage d;
    if (bytes.size() < 8 || bytes.compare(0, 4, "TPLV") != 0) return d;
    std::uint32_t n = 0;
    for (int i = 0; i < 4; ++i)
        n |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[4 + i])) << (8 * i);
    d.header = nlohmann::json::parse(bytes.substr(8, n));
    const std::size_t pixels =
        d.header["width"].get<std::size_t>() * d.header["height"].get<std::size_t>();
    std::size_t at = 8 + n;
    for (std::size_t c = 0; c < d.header["channels"].size(); ++c) {
        std::vector<std::uint16_t> q(pixels);
        for (std::size_t i = 0; i < pixels; ++i, at += 2)
            q[i] = static_cast<std::uint16_t>(static_cast<unsigned char>(bytes[at]) |
                                              (static_cast<unsigned char>(bytes[at + 1]) << 8));
        d.codes.push_back(std::move(q));
    }
    return d;
}

}  // namespace tirpol::test
