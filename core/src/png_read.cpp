#include "png_read.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <memory>
#include <string>

#include "tirpol/core/error.h"

namespace tirpol::detail {

namespace {
// Everything the decode touches lives here, on the heap: after libpng's longjmp only memory reached
// through a pointer set before setjmp is reliable, never a local variable changed since.
struct Session {
    std::FILE* file = nullptr;
    png_structp png = nullptr;
    png_infop info = nullptr;
    std::string error;
    PngCounts out;
    std::vector<png_bytep> rows;

    ~Session() {
        if (png) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
        if (file) std::fclose(file);
    }
};

[[noreturn]] void on_error(png_structp png, png_const_charp message) {
    static_cast<Session*>(png_get_error_ptr(png))->error = message;
    png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

int channels_of(int colour_type) {
    switch (colour_type) {
        case PNG_COLOR_TYPE_GRAY:
            return 1;
        case PNG_COLOR_TYPE_GRAY_ALPHA:
            return 2;
        case PNG_COLOR_TYPE_RGB:
            return 3;
        case PNG_COLOR_TYPE_RGB_ALPHA:
            return 4;
        default:
            return 1;  // palette: 8 bits at most, refused by the bit-depth check
    }
}
}  // namespace

PngCounts read_png_counts(const std::filesystem::path& path) {
    const auto s = std::make_unique<Session>();
    s->file = std::fopen(path.c_str(), "rb");
    if (!s->file) fail("{}: cannot open", path.string());
    s->png = png_create_read_struct(PNG_LIBPNG_VER_STRING, s.get(), on_error, on_warning);
    if (s->png) s->info = png_create_info_struct(s->png);
    if (!s->png || !s->info) fail("{}: libpng could not start (out of memory?)", path.string());
    if (setjmp(png_jmpbuf(s->png)))
        fail("{}: cannot be decoded as PNG: {}", path.string(), s->error);

    png_init_io(s->png, s->file);
    png_read_info(s->png, s->info);
    const int colour_type = png_get_color_type(s->png, s->info);
    if (channels_of(colour_type) != 1)
        fail("{}: has {} channels; expected a single-channel raw image", path.string(),
             channels_of(colour_type));
    if (png_get_bit_depth(s->png, s->info) != 16)
        fail("{}: is a {}-bit PNG, which cannot hold camera counts; expected a 16-bit raw image",
             path.string(), png_get_bit_depth(s->png, s->info));
    if (png_get_valid(s->png, s->info, PNG_INFO_tRNS))
        fail("{}: has a transparency (tRNS) chunk; expected a plain single-channel raw image",
             path.string());
    // PNG stores 16-bit samples big-endian.
    const std::uint16_t probe = 1;
    if (*reinterpret_cast<const std::uint8_t*>(&probe) == 1) png_set_swap(s->png);
    png_set_interlace_handling(s->png);
    png_read_update_info(s->png, s->info);

    s->out.width = static_cast<int>(png_get_image_width(s->png, s->info));
    s->out.height = static_cast<int>(png_get_image_height(s->png, s->info));
    const auto width = static_cast<std::size_t>(s->out.width),
               height = static_cast<std::size_t>(s->out.height);
    s->out.counts.resize(width * height);
    s->rows.resize(height);
    for (std::size_t y = 0; y < height; ++y)
        s->rows[y] = reinterpret_cast<png_bytep>(s->out.counts.data() + y * width);
    png_read_image(s->png, s->rows.data());
    png_read_end(s->png, nullptr);
    return std::move(s->out);
}

}  // namespace tirpol::detail
