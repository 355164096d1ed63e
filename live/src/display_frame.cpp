#include "display_frame.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "tirpol/core/error.h"

namespace tirpol::live {

namespace {
constexpr std::uint16_t kCodeNone = 0, kCodeDead = 1, kCodeSaturated = 65535, kCodeFirst = 2;
constexpr double kCodeSpan = 65532.0;

void append_u32(std::string& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}
}  // namespace

DisplayUnit parse_display_unit(const std::string& text) {
    if (text == "counts") return DisplayUnit::Counts;
    if (text == "radiance") return DisplayUnit::Radiance;
    if (text == "temperature") return DisplayUnit::Temperature;
    fail("live view: display unit '{}': expected counts, radiance or temperature", text);
}

DisplayConverter::DisplayConverter(const acquisition::CameraInfo& camera,
                                   const calibration::RadiometricCalibration* calibration,
                                   DisplayUnit unit)
    : m_calibration(calibration), m_unit(unit), m_width(camera.width), m_height(camera.height) {
    if (unit != DisplayUnit::Counts && calibration == nullptr)
        fail(
            "live view: showing radiance or temperature needs a radiometric calibration "
            "(--calibration)");
    if (calibration && (calibration->width != camera.width || calibration->height != camera.height))
        fail("live view: the calibration is {}×{} pixels but the camera {} streams {}×{}",
             calibration->width, calibration->height, camera.uri, camera.width, camera.height);
    // Integer formats clip at full scale; a float camera (bits 0 or ≥ 24) has no saturation code.
    if (camera.bits_per_pixel >= 1 && camera.bits_per_pixel <= 23)
        m_saturation_counts = std::ldexp(1.0, camera.bits_per_pixel) - 1.0;
}

std::string DisplayConverter::units() const {
    switch (m_unit) {
        case DisplayUnit::Counts:
            return "counts";
        case DisplayUnit::Radiance:
            return "W/(m²·sr)";
        case DisplayUnit::Temperature:
            return "K";
    }
    return "";
}

std::vector<float> DisplayConverter::to_signal(const std::vector<float>& counts,
                                               std::optional<double> fpa_temperature_k) const {
    if (!m_calibration) return counts;
    return calibration::counts_to_radiance(*m_calibration, counts, fpa_temperature_k);
}

std::vector<float> DisplayConverter::convert(const std::vector<float>& counts,
                                             std::optional<double> fpa_temperature_k) const {
    if (m_unit == DisplayUnit::Counts) return counts;
    std::vector<float> radiance = to_signal(counts, fpa_temperature_k);
    if (m_unit == DisplayUnit::Radiance) return radiance;
    return calibration::brightness_temperature(m_calibration->band(), radiance);
}

std::vector<std::uint8_t> DisplayConverter::flags(const std::vector<float>& counts) const {
    std::vector<std::uint8_t> f(counts.size(), kPixelOk);
    for (std::size_t i = 0; i < counts.size(); ++i) {
        const bool dead = m_calibration ? m_calibration->bad[i] != 0.0f : counts[i] <= 0.0f;
        if (dead)
            f[i] = kPixelDead;
        else if (m_saturation_counts && counts[i] >= *m_saturation_counts)
            f[i] = kPixelSaturated;
    }
    return f;
}

DisplayImage DisplayConverter::frame_image(const acquisition::Frame& frame) const {
    DisplayImage image;
    image.width = frame.width;
    image.height = frame.height;
    image.channels.push_back(
        {"S0", units(), convert(frame.counts, frame.fpa_temperature_k), flags(frame.counts)});
    image.info["frame_id"] = frame.frame_id;
    image.info["host_timestamp_ns"] = frame.host_timestamp_ns;
    if (frame.fpa_temperature_k) image.info["fpa_temperature_k"] = *frame.fpa_temperature_k;
    return image;
}

std::string encode_display_image(const DisplayImage& image) {
    const std::size_t pixels =
        static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    nlohmann::json header = image.info;
    header["width"] = image.width;
    header["height"] = image.height;
    header["channels"] = nlohmann::json::array();
    std::vector<std::vector<std::uint16_t>> codes;
    for (const auto& c : image.channels) {
        if (c.values.size() != pixels || (!c.flags.empty() && c.flags.size() != pixels))
            fail("live view: channel {} has {} values for a {}×{} image", c.name, c.values.size(),
                 image.width, image.height);
        auto flag = [&](std::size_t i) {
            return c.flags.empty() ? std::uint8_t{kPixelOk} : c.flags[i];
        };
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (std::size_t i = 0; i < pixels; ++i)
            if (flag(i) == kPixelOk && std::isfinite(c.values[i])) {
                lo = std::min(lo, static_cast<double>(c.values[i]));
                hi = std::max(hi, static_cast<double>(c.values[i]));
            }
        if (!(lo <= hi)) lo = hi = 0.0;
        const double scale = hi > lo ? kCodeSpan / (hi - lo) : 0.0;
        std::vector<std::uint16_t> q(pixels);
        for (std::size_t i = 0; i < pixels; ++i) {
            if (flag(i) == kPixelDead)
                q[i] = kCodeDead;
            else if (flag(i) == kPixelSaturated)
                q[i] = kCodeSaturated;
            else if (!std::isfinite(c.values[i]))
                q[i] = kCodeNone;
            else
                q[i] = static_cast<std::uint16_t>(kCodeFirst +
                                                  std::lround((c.values[i] - lo) * scale));
        }
        codes.push_back(std::move(q));
        header["channels"].push_back(
            {{"name", c.name}, {"units", c.units}, {"min", lo}, {"max", hi}});
    }
    std::string text = header.dump();
    if (text.size() % 2 != 0)
        text.push_back(' ');  // u16 data stays 2-byte aligned for the page's Uint16Array
    std::string out = "TPLV";
    append_u32(out, static_cast<std::uint32_t>(text.size()));
    out += text;
    for (const auto& q : codes) {
        const std::size_t at = out.size();
        out.resize(at + q.size() * 2);
        for (std::size_t i = 0; i < q.size(); ++i) {
            out[at + 2 * i] = static_cast<char>(q[i] & 0xffu);
            out[at + 2 * i + 1] = static_cast<char>(q[i] >> 8);
        }
    }
    return out;
}

}  // namespace tirpol::live
