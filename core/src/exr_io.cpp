#include "tirpol/core/exr_io.h"

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
#include <Iex.h>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"

namespace tirpol {

namespace {
// Attributes OpenEXR manages itself; not copied into Image::attributes().
bool is_structural(const std::string& name) {
    static const char* const kNames[] = {"channels", "compression", "dataWindow", "displayWindow", "lineOrder",
                                         "pixelAspectRatio", "screenWindowCenter", "screenWindowWidth"};
    for (const char* n : kNames)
        if (name == n) return true;
    return false;
}
}  // namespace

void write_exr(const std::filesystem::path& path, const Image& image) {
    if (image.channel_names().empty()) fail("{}: refusing to write an image with no channels", path.string());
    AtomicFile file(path);
    try {
        Imf::Header header(image.width(), image.height());
        header.compression() = Imf::ZIP_COMPRESSION;
        for (const auto& [name, value] : image.attributes()) {
            std::visit(
                [&, &key = name](const auto& v) {
                    using T = std::decay_t<decltype(v)>;
                    if constexpr (std::is_same_v<T, int>) header.insert(key, Imf::IntAttribute(v));
                    else if constexpr (std::is_same_v<T, double>) header.insert(key, Imf::DoubleAttribute(v));
                    else if constexpr (std::is_same_v<T, std::string>) header.insert(key, Imf::StringAttribute(v));
                    else {
                        std::vector<float> f(v.begin(), v.end());
                        header.insert(key, Imf::FloatVectorAttribute(f));
                    }
                },
                value);
        }
        Imf::FrameBuffer fb;
        const std::size_t xs = sizeof(float), ys = sizeof(float) * static_cast<std::size_t>(image.width());
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
    if (!std::filesystem::exists(path)) fail("{}: no such file", path.string());
    bool tiled = false, deep = false, multipart = false;
    if (!Imf::isOpenExrFile(path.c_str(), tiled, deep, multipart))
        fail("{}: not an OpenEXR file (bad magic number or header)", path.string());
    if (deep) fail("{}: deep OpenEXR images are not supported", path.string());
    try {
        Imf::InputFile in(path.c_str());
        if (!in.isComplete())
            fail("{}: the OpenEXR file is truncated or incomplete (missing scan lines or tiles)", path.string());
        const Imath::Box2i dw = in.header().dataWindow();
        const int width = dw.max.x - dw.min.x + 1, height = dw.max.y - dw.min.y + 1;
        Image image(width, height);
        Imf::FrameBuffer fb;
        const std::size_t xs = sizeof(float), ys = sizeof(float) * static_cast<std::size_t>(width);
        for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) {
            if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
                fail("{}: channel '{}' is subsampled, which tirpol does not read", path.string(), it.name());
            auto& plane = image.add_channel(it.name());
            char* base = reinterpret_cast<char*>(plane.data()) -
                         (static_cast<std::ptrdiff_t>(dw.min.x) + static_cast<std::ptrdiff_t>(dw.min.y) * width) *
                             static_cast<std::ptrdiff_t>(sizeof(float));
            fb.insert(it.name(), Imf::Slice(Imf::FLOAT, base, xs, ys));
        }
        in.setFrameBuffer(fb);
        in.readPixels(dw.min.y, dw.max.y);
        for (auto it = in.header().begin(); it != in.header().end(); ++it) {
            const std::string name = it.name();
            if (is_structural(name)) continue;
            const Imf::Attribute& a = it.attribute();
            if (auto* i = dynamic_cast<const Imf::IntAttribute*>(&a)) image.attributes()[name] = i->value();
            else if (auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&a)) image.attributes()[name] = d->value();
            else if (auto* f = dynamic_cast<const Imf::FloatAttribute*>(&a))
                image.attributes()[name] = static_cast<double>(f->value());
            else if (auto* s = dynamic_cast<const Imf::StringAttribute*>(&a)) image.attributes()[name] = s->value();
            else if (auto* v = dynamic_cast<const Imf::FloatVectorAttribute*>(&a))
                image.attributes()[name] = std::vector<double>(v->value().begin(), v->value().end());
        }
        return image;
    } catch (const Iex::BaseExc& e) {
        fail("{}: corrupt or truncated OpenEXR file: {}", path.string(), e.what());
    }
}

}  // namespace tirpol
