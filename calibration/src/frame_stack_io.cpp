#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <set>

#include "tirpol/calibration/noise.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/output_guard.h"

namespace tirpol::calibration {

namespace fs = std::filesystem;

namespace {
const std::set<std::string> kFrameExtensions{".exr", ".png", ".tif", ".tiff"};

std::size_t bytes_per_value(RawFrameFormat::Type type) {
    switch (type) {
        case RawFrameFormat::Type::UInt8:
            return 1;
        case RawFrameFormat::Type::UInt16:
            return 2;
        case RawFrameFormat::Type::Float32:
            return 4;
    }
    return 0;
}

std::string lower_extension(const fs::path& p) {
    std::string e = p.extension().string();
    std::transform(e.begin(), e.end(), e.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return e;
}

FrameStack load_raw(const fs::path& path, const RawFrameFormat& raw) {
    if (raw.width < 1 || raw.height < 1)
        fail("{}: raw frame shape {}×{}; expected a width and a height ≥ 1", path.string(),
             raw.width, raw.height);
    const std::size_t n =
        static_cast<std::size_t>(raw.width) * static_cast<std::size_t>(raw.height);
    const std::size_t frame_bytes = n * bytes_per_value(raw.type);
    // A raw stack has no fixed size limit: its decoded floats must fit in memory instead.
    check_input_file(path, std::numeric_limits<std::uintmax_t>::max());
    const std::size_t size = fs::file_size(path);
    if (size < raw.header_bytes || (size - raw.header_bytes) % frame_bytes != 0)
        fail(
            "{}: {} bytes is not {} header bytes + a whole number of {}×{} frames of {} bytes "
            "each; check the shape, "
            "the value type and the header size",
            path.string(), size, raw.header_bytes, raw.width, raw.height, frame_bytes);
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(raw.header_bytes));
    FrameStack stack;
    stack.width = raw.width;
    stack.height = raw.height;
    std::vector<unsigned char> buffer(frame_bytes);
    for (std::size_t f = 0; f < (size - raw.header_bytes) / frame_bytes; ++f) {
        if (!in.read(reinterpret_cast<char*>(buffer.data()),
                     static_cast<std::streamsize>(frame_bytes)))
            fail("{}: read failed at frame {}", path.string(), f);
        std::vector<float> frame(n);
        for (std::size_t i = 0; i < n; ++i) {
            const unsigned char* b = buffer.data() + i * bytes_per_value(raw.type);
            switch (raw.type) {  // little-endian, independent of the host
                case RawFrameFormat::Type::UInt8:
                    frame[i] = b[0];
                    break;
                case RawFrameFormat::Type::UInt16:
                    frame[i] = static_cast<float>(b[0] | (b[1] << 8));
                    break;
                case RawFrameFormat::Type::Float32: {
                    const std::uint32_t bits = static_cast<std::uint32_t>(b[0]) |
                                               (static_cast<std::uint32_t>(b[1]) << 8) |
                                               (static_cast<std::uint32_t>(b[2]) << 16) |
                                               (static_cast<std::uint32_t>(b[3]) << 24);
                    std::memcpy(&frame[i], &bits, 4);
                    break;
                }
            }
        }
        stack.frames.push_back(std::move(frame));
    }
    return stack;
}
}  // namespace

RawFrameFormat::Type raw_type_from_string(const std::string& text) {
    if (text == "uint8") return RawFrameFormat::Type::UInt8;
    if (text == "uint16") return RawFrameFormat::Type::UInt16;
    if (text == "float32") return RawFrameFormat::Type::Float32;
    fail("raw value type '{}'; expected uint8, uint16 or float32", text);
}

FrameStack load_frame_stack(const fs::path& path, const std::optional<RawFrameFormat>& raw) {
    FrameStack stack;
    if (raw) {
        stack = load_raw(path, *raw);
    } else if (fs::is_directory(path)) {
        std::vector<fs::path> files;
        for (const auto& e : fs::directory_iterator(path))
            if (e.is_regular_file() && kFrameExtensions.count(lower_extension(e.path())))
                files.push_back(e.path());
        if (files.empty())
            fail(
                "{}: no frame files (.exr, .png, .tif, .tiff); for a raw file give its shape "
                "(--raw-shape)",
                path.string());
        std::sort(files.begin(), files.end());
        for (const auto& f : files) {
            const Image im = read_raw_image(f, "counts", "counts");
            if (stack.frames.empty()) {
                stack.width = im.width();
                stack.height = im.height();
            }
            if (im.width() != stack.width || im.height() != stack.height)
                fail("{}: frame is {}×{}, the first frame of the stack is {}×{}", f.string(),
                     im.width(), im.height(), stack.width, stack.height);
            stack.frames.push_back(im.channel("counts"));
        }
    } else if (lower_extension(path) == ".exr") {
        const Image im = read_exr(path);
        stack.width = im.width();
        stack.height = im.height();
        std::vector<std::string> names;
        for (const auto& n : im.channel_names())
            if (n.rfind("frame_", 0) == 0) names.push_back(n);
        std::sort(names.begin(), names.end());
        for (const auto& n : names) stack.frames.push_back(im.channel(n));
    } else {
        fail(
            "{}: expected a directory of frames, an EXR with frame_* channels, or a raw file with "
            "its shape "
            "(--raw-shape)",
            path.string());
    }
    validate_stack(stack, path.c_str());
    return stack;
}

FrameStack temperature_stack(const FrameStack& counts, const RadiometricCalibration& cal,
                             std::optional<double> fpa_temperature_k) {
    if (counts.width != cal.width || counts.height != cal.height)
        fail("the stack is {}×{} but the calibration is {}×{}", counts.width, counts.height,
             cal.width, cal.height);
    FrameStack out;
    out.width = counts.width;
    out.height = counts.height;
    double sum = 0.0, count = 0.0;
    for (const auto& f : counts.frames) {
        out.frames.push_back(counts_to_radiance(cal, f, fpa_temperature_k));
        for (float l : out.frames.back())
            if (std::isfinite(l)) {
                sum += l;
                count += 1.0;
            }
    }
    if (count == 0.0) fail("no finite radiance in the calibrated stack (every pixel bad?)");
    const Band band = cal.band();
    const double t0 = band.brightness_temperature(sum / count);
    const double l0 = band.radiance(t0), dl_dt = band.radiance_dT(t0);
    for (auto& f : out.frames)
        for (float& v : f) v = static_cast<float>(t0 + (v - l0) / dl_dt);
    return out;
}

}  // namespace tirpol::calibration
