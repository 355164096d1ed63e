#include "tirpol/core/exr_io.h"

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFloatAttribute.h>
#include <ImfFloatVectorAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfTestFile.h>

#include <cstdint>
#include <fstream>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/core/utf8.h"

namespace tirpol {

namespace {
// Attributes OpenEXR manages itself; not copied into Image::attributes().
bool is_structural(const std::string& name) {
    static const char* const kNames[] = {
        "channels",  "compression",      "dataWindow",         "displayWindow",
        "lineOrder", "pixelAspectRatio", "screenWindowCenter", "screenWindowWidth"};
    for (const char* n : kNames)
        if (name == n) return true;
    return false;
}

// OpenEXR's own sanity check rejects a larger data window or tile while reading the header,
// before it sizes its offset tables from it.
void limit_openexr_header_sizes() {
    static const bool once = [] {
        Imf::Header::setMaxImageSize(limits::kMaxImageSide, limits::kMaxImageSide);
        Imf::Header::setMaxTileSize(limits::kMaxImageSide, limits::kMaxImageSide);
        return true;
    }();
    (void)once;
}

// OpenEXR allocates each attribute's declared size before it reads the value (an attribute of an
// unknown type becomes an OpaqueAttribute: `new char[size]`), so a 300-byte file declaring a 1.6 GB
// attribute costs a 1.6 GB allocation or std::bad_alloc. Walks the header(s) first, as laid out in
// "OpenEXR File Layout" (name\0 type\0 int32 size, value; an empty name ends a header; with the
// multi-part flag, an empty header ends the list), and refuses a size beyond the bytes left in the
// file. What this walk cannot follow is left to OpenEXR's own checks.
void check_attribute_sizes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    const auto file_bytes = static_cast<std::int64_t>(std::filesystem::file_size(path));
    std::uint8_t version[8];
    if (!in.read(reinterpret_cast<char*>(version), sizeof version)) return;
    const bool multipart = (version[5] & 0x10) != 0;  // flag bit 12 of the version field
    auto read_text = [&](std::string& out) {          // a null-terminated name, at most 255 bytes
        out.clear();
        for (char c = 0; in.get(c);) {
            if (c == '\0') return true;
            if (out.size() == 255) return false;
            out += c;
        }
        return false;
    };
    std::string name, type;
    for (bool header_was_empty = false; !header_was_empty;) {
        header_was_empty = true;
        while (read_text(name) && !name.empty()) {
            header_was_empty = false;
            std::uint8_t size_le[4];
            if (!read_text(type) || !in.read(reinterpret_cast<char*>(size_le), sizeof size_le))
                return;
            const auto size = static_cast<std::int32_t>(
                static_cast<std::uint32_t>(size_le[0]) | std::uint32_t{size_le[1]} << 8 |
                std::uint32_t{size_le[2]} << 16 | std::uint32_t{size_le[3]} << 24);
            const std::int64_t left = file_bytes - static_cast<std::int64_t>(in.tellg());
            if (size < 0 || size > left)
                fail(
                    "{}: header attribute '{}' ({}) declares {} bytes, but the file has only {} "
                    "left (corrupt or "
                    "truncated header)",
                    path.string(), name, type, size, left);
            in.seekg(size, std::ios::cur);
        }
        if (!in || !multipart) return;
    }
}

// Most decoded bytes a compression can produce per file byte: none stores them as they are; RLE
// codes at most 128 equal bytes in 2 (ImfRle.cpp); zlib's deflate reaches at most 1032:1 (ZIP,
// ZIPS; PXR24 first keeps 3 of every 4 float bytes); B44 stores a 4×4 block of halves in 14 bytes,
// B44A a flat one in 3. PIZ and DWA have no simple bound: limits::kMaxCompressionRatio.
double max_compression_ratio(Imf::Compression compression) {
    switch (compression) {
        case Imf::NO_COMPRESSION:
            return 1.0;
        case Imf::RLE_COMPRESSION:
            return 64.0;
        case Imf::ZIPS_COMPRESSION:
        case Imf::ZIP_COMPRESSION:
            return 1032.0;
        case Imf::PXR24_COMPRESSION:
            return 1032.0 * 4.0 / 3.0;
        case Imf::B44_COMPRESSION:
            return 32.0 / 14.0;
        case Imf::B44A_COMPRESSION:
            return 32.0 / 3.0;
        default:
            return limits::kMaxCompressionRatio;
    }
}

// Checks the declared size before any pixel is allocated: against tirpol's limits, and against
// the file's size under the file's own compression (a 480 KB file cannot hold 40000×40000 pixels).
void check_declared_size(const std::filesystem::path& path, std::int64_t width, std::int64_t height,
                         const Imf::Header& header) {
    if (width <= 0 || height <= 0)
        fail("{}: the OpenEXR data window is empty or inverted ({}×{})", path.string(), width,
             height);
    const auto pixels = static_cast<double>(width) * static_cast<double>(height);
    if (width > limits::kMaxImageSide || height > limits::kMaxImageSide ||
        pixels > static_cast<double>(limits::kMaxImagePixels))
        fail(
            "{}: declares {}×{} pixels, beyond tirpol's limits ({} pixels a side, {} pixels in "
            "all)",
            path.string(), width, height, limits::kMaxImageSide, limits::kMaxImagePixels);
    double decoded_bytes = 0.0;
    int channel_count = 0;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it, ++channel_count)
        decoded_bytes += pixels * (it.channel().type == Imf::HALF ? 2.0 : 4.0);
    const auto file_bytes = static_cast<double>(std::filesystem::file_size(path));
    const double max_ratio = max_compression_ratio(header.compression());
    if (decoded_bytes > max_ratio * file_bytes)
        fail(
            "{}: declares {}×{} pixels in {} channel(s) ({:.3g} bytes decoded) but the file has "
            "only {} bytes; "
            "no OpenEXR compression reaches that ratio (at most {:.4g}:1 for this file's "
            "compression; corrupt "
            "header or truncated file?)",
            path.string(), width, height, channel_count, decoded_bytes, file_bytes, max_ratio);
}
}  // namespace

void write_exr(const std::filesystem::path& path, const Image& image) {
    if (image.channel_names().empty())
        fail("{}: refusing to write an image with no channels", path.string());
    // OpenEXR stores names as NUL-terminated UTF-8: a name with a NUL would be cut short (and two
    // channels could collide), invalid UTF-8 would be unreadable to other tools.
    const auto check_name = [&](const std::string& name, const char* kind) {
        if (name.empty()) fail("{}: an empty {} name", path.string(), kind);
        if (name.find('\0') != std::string::npos)
            fail("{}: {} name '{}' contains a NUL byte; EXR names cannot", path.string(), kind,
                 valid_utf8(name.substr(0, name.find('\0'))) + "\\0…");
        if (!is_valid_utf8(name))
            fail("{}: {} name '{}' is not valid UTF-8", path.string(), kind, valid_utf8(name));
    };
    for (const std::string& name : image.channel_names()) check_name(name, "channel");
    for (const auto& [name, value] : image.attributes()) check_name(name, "attribute");
    AtomicFile file(path);
    try {
        Imf::Header header(image.width(), image.height());
        header.compression() = Imf::ZIP_COMPRESSION;
        for (const auto& [name, value] : image.attributes()) {
            std::visit(
                [&, &key = name](const auto& v) {
                    using T = std::decay_t<decltype(v)>;
                    if constexpr (std::is_same_v<T, int>)
                        header.insert(key, Imf::IntAttribute(v));
                    else if constexpr (std::is_same_v<T, double>)
                        header.insert(key, Imf::DoubleAttribute(v));
                    else if constexpr (std::is_same_v<T, std::string>)
                        header.insert(key, Imf::StringAttribute(v));
                    else {
                        std::vector<float> f(v.begin(), v.end());
                        header.insert(key, Imf::FloatVectorAttribute(f));
                    }
                },
                value);
        }
        Imf::FrameBuffer fb;
        const std::size_t xs = sizeof(float),
                          ys = sizeof(float) * static_cast<std::size_t>(image.width());
        for (const auto& name : image.channel_names()) {
            header.channels().insert(name, Imf::Channel(Imf::FLOAT));
            auto* base = const_cast<float*>(image.channel(name).data());
            fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(base), xs, ys));
        }
        Imf::OutputFile out(file.temp_path().c_str(), header);
        out.setFrameBuffer(fb);
        out.writePixels(image.height());
    } catch (const Iex::BaseExc& e) {
        fail("{}: writing OpenEXR failed: {}", path.string(), e.what());
    }
    file.commit();
}

Image read_exr(const std::filesystem::path& path) {
    check_input_file(path, limits::kMaxImageFileBytes);
    bool tiled = false, deep = false, multipart = false;
    if (!Imf::isOpenExrFile(path.c_str(), tiled, deep, multipart))
        fail("{}: not an OpenEXR file (bad magic number or header)", path.string());
    if (deep) fail("{}: deep OpenEXR images are not supported", path.string());
    limit_openexr_header_sizes();
    check_attribute_sizes(path);
    try {
        Imf::InputFile in(path.c_str());
        const Imath::Box2i dw = in.header().dataWindow();
        const std::int64_t width = std::int64_t{dw.max.x} - dw.min.x + 1,
                           height = std::int64_t{dw.max.y} - dw.min.y + 1;
        check_declared_size(path, width, height, in.header());
        if (!in.isComplete())
            fail("{}: the OpenEXR file is truncated or incomplete (missing scan lines or tiles)",
                 path.string());
        Image image(static_cast<int>(width), static_cast<int>(height));
        Imf::FrameBuffer fb;
        const std::size_t xs = sizeof(float), ys = sizeof(float) * static_cast<std::size_t>(width);
        for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) {
            if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
                fail("{}: channel '{}' is subsampled, which tirpol does not read", path.string(),
                     it.name());
            auto& plane = image.add_channel(it.name());
            char* base = reinterpret_cast<char*>(plane.data()) -
                         (static_cast<std::ptrdiff_t>(dw.min.x) +
                          static_cast<std::ptrdiff_t>(dw.min.y) * width) *
                             static_cast<std::ptrdiff_t>(sizeof(float));
            fb.insert(it.name(), Imf::Slice(Imf::FLOAT, base, xs, ys));
        }
        in.setFrameBuffer(fb);
        in.readPixels(dw.min.y, dw.max.y);
        for (auto it = in.header().begin(); it != in.header().end(); ++it) {
            const std::string name = it.name();
            if (is_structural(name)) continue;
            const Imf::Attribute& a = it.attribute();
            if (auto* i = dynamic_cast<const Imf::IntAttribute*>(&a))
                image.attributes()[name] = i->value();
            else if (auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&a))
                image.attributes()[name] = d->value();
            else if (auto* f = dynamic_cast<const Imf::FloatAttribute*>(&a))
                image.attributes()[name] = static_cast<double>(f->value());
            else if (auto* s = dynamic_cast<const Imf::StringAttribute*>(&a))
                image.attributes()[name] = s->value();
            else if (auto* v = dynamic_cast<const Imf::FloatVectorAttribute*>(&a))
                image.attributes()[name] =
                    std::vector<double>(v->value().begin(), v->value().end());
        }
        return image;
    } catch (const Iex::BaseExc& e) {
        fail("{}: unreadable OpenEXR file (corrupt, truncated or beyond limits): {}", path.string(),
             e.what());
    }
}

}  // namespace tirpol
