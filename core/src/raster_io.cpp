#include <tiffio.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "png_read.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"

namespace tirpol {

namespace {
std::uint32_t big_endian_u32(const unsigned char* p) {
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
           p[3];
}

// A header's declared size against tirpol's limits, before anything is allocated for it.
void check_declared_size(const std::filesystem::path& path, std::uint32_t width,
                         std::uint32_t height) {
    if (width == 0 || height == 0 || width > limits::kMaxImageSide ||
        height > limits::kMaxImageSide || std::uint64_t{width} * height > limits::kMaxImagePixels)
        fail(
            "{}: declares {}×{} pixels, beyond tirpol's limits ({} pixels a side, {} pixels in "
            "all)",
            path.string(), width, height, limits::kMaxImageSide, limits::kMaxImagePixels);
}

// Checks a PNG's IHDR (size, bit depth) before decoding, so that a declared 40000×40000 or an
// 8-bit image is refused without allocating its pixels.
void check_png_header(const std::filesystem::path& path) {
    unsigned char h[26] = {};
    std::ifstream in(path, std::ios::binary);
    in.read(reinterpret_cast<char*>(h), sizeof h);
    static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (in.gcount() != sizeof h || !std::equal(kSignature, kSignature + 8, h) ||
        std::memcmp(h + 12, "IHDR", 4) != 0)
        fail("{}: not a PNG file (bad signature or no IHDR chunk)", path.string());
    const std::uint32_t width = big_endian_u32(h + 16), height = big_endian_u32(h + 20);
    const int bit_depth = h[24];
    check_declared_size(path, width, height);
    const double decoded_bytes = static_cast<double>(width) * height * std::max(bit_depth, 8) / 8.0;
    if (decoded_bytes >
        limits::kMaxCompressionRatio * static_cast<double>(std::filesystem::file_size(path)))
        fail("{}: declares {}×{} pixels, more than the file's {} bytes can hold (corrupt header?)",
             path.string(), width, height, std::filesystem::file_size(path));
    if (bit_depth < 16)
        fail("{}: is a {}-bit PNG, which cannot hold camera counts; expected a 16-bit raw image",
             path.string(), bit_depth);
}

// The same for a TIFF, with libtiff reading only the first directory's tags (OpenCV would decode
// first and check after). libtiff's own messages are silenced; its failure becomes our error.
void check_tiff_header(const std::filesystem::path& path) {
    TIFFSetErrorHandler(nullptr);
    TIFFSetWarningHandler(nullptr);
    const std::unique_ptr<TIFF, void (*)(TIFF*)> tiff(TIFFOpen(path.c_str(), "r"), TIFFClose);
    if (!tiff)
        fail("{}: not a TIFF file (bad header or unreadable first directory)", path.string());
    std::uint32_t width = 0, height = 0;
    std::uint16_t bits = 0, samples = 1;
    if (TIFFGetField(tiff.get(), TIFFTAG_IMAGEWIDTH, &width) != 1 ||
        TIFFGetField(tiff.get(), TIFFTAG_IMAGELENGTH, &height) != 1)
        fail("{}: TIFF without ImageWidth/ImageLength tags", path.string());
    TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_BITSPERSAMPLE, &bits);
    TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_SAMPLESPERPIXEL, &samples);
    check_declared_size(path, width, height);
    const double decoded_bytes =
        static_cast<double>(width) * height * samples * std::max<int>(bits, 8) / 8.0;
    if (decoded_bytes >
        limits::kMaxCompressionRatio * static_cast<double>(std::filesystem::file_size(path)))
        fail("{}: declares {}×{} pixels, more than the file's {} bytes can hold (corrupt header?)",
             path.string(), width, height, std::filesystem::file_size(path));
}
Image counts_image(const detail::PngCounts& png, const std::string& channel_name) {
    Image out(png.width, png.height);
    out.set_channel(channel_name, std::vector<float>(png.counts.begin(), png.counts.end()));
    out.attributes()["source_depth_bits"] = 16;
    return out;
}
}  // namespace

Image read_raw_image(const std::filesystem::path& path, const std::string& channel_name,
                     const std::string& exr_channel) {
    check_input_file(path, limits::kMaxImageFileBytes);
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".exr") {
        const Image exr = read_exr(path);
        if (!exr.has_channel(exr_channel))
            fail("{}: no channel '{}' (raw counts expected)", path.string(), exr_channel);
        Image out(exr.width(), exr.height());
        out.set_channel(channel_name, exr.channel(exr_channel));
        out.attributes() = exr.attributes();
        return out;
    }
    if (ext != ".png" && ext != ".tif" && ext != ".tiff")
        fail("{}: unsupported raw image type '{}'; expected .exr, .png or .tif/.tiff",
             path.string(), ext);
    if (!std::filesystem::exists(path)) fail("{}: no such file", path.string());
    if (ext == ".png") {
        check_png_header(path);
        return counts_image(detail::read_png_counts(path), channel_name);
    }
    check_tiff_header(path);
    const cv::Mat m = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
    if (m.empty()) fail("{}: cannot be decoded as {} (truncated or corrupt?)", path.string(), ext);
    if (m.channels() != 1)
        fail("{}: has {} channels; expected a single-channel raw image", path.string(),
             m.channels());
    if (m.depth() == CV_8U || m.depth() == CV_8S)
        fail(
            "{}: is an 8-bit image, which cannot hold camera counts; expected 16-bit integer or "
            "32-bit float raw "
            "counts (an 8-bit export is a display rendering, or its BitsPerSample is corrupt)",
            path.string());
    cv::Mat f;
    m.convertTo(f, CV_32F);
    Image out(f.cols, f.rows);
    std::vector<float> plane(static_cast<std::size_t>(f.cols) * static_cast<std::size_t>(f.rows));
    for (int y = 0; y < f.rows; ++y)
        std::copy_n(f.ptr<float>(y), f.cols,
                    plane.begin() + static_cast<std::ptrdiff_t>(y) * f.cols);
    out.set_channel(channel_name, std::move(plane));
    out.attributes()["source_depth_bits"] = static_cast<int>(m.elemSize1() * 8);
    return out;
}

}  // namespace tirpol
