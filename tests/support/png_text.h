#pragma once
// The text chunks of a PNG file (tEXt and uncompressed iTXt), read chunk by chunk with each chunk's
// CRC-32 checked by a bitwise implementation of its own (PNG specification §5.3, Annex D), so that
// a test does not trust the writer's checksum code to check its output.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string>

namespace tirpol::test {

inline std::uint32_t png_crc32(const std::string& bytes) {
    std::uint32_t crc = 0xffffffffu;
    for (const char c : bytes) {
        crc ^= static_cast<unsigned char>(c);
        for (int k = 0; k < 8; ++k) crc = (crc & 1u) ? (crc >> 1) ^ 0xedb88320u : crc >> 1;
    }
    return crc ^ 0xffffffffu;
}

/// keyword → text of every tEXt and iTXt chunk; throws std::runtime_error for a file that is not
/// a PNG, a truncated chunk or a CRC mismatch.
inline std::map<std::string, std::string> png_text_chunks(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string png{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (png.size() < 8 || png.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0)
        throw std::runtime_error(path.string() + ": not a PNG");
    const auto u32 = [&](std::size_t at) {
        std::uint32_t v = 0;
        for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(png[at + i]);
        return v;
    };
    std::map<std::string, std::string> text;
    for (std::size_t at = 8; at < png.size();) {
        if (at + 12 > png.size()) throw std::runtime_error(path.string() + ": truncated chunk");
        const std::size_t length = u32(at);
        if (at + 12 + length > png.size())
            throw std::runtime_error(path.string() + ": truncated chunk");
        const std::string type = png.substr(at + 4, 4), data = png.substr(at + 8, length);
        if (png_crc32(type + data) != u32(at + 8 + length))
            throw std::runtime_error(path.string() + ": CRC mismatch in chunk " + type);
        const std::size_t nul = data.find('\0');
        if (type == "tEXt" && nul != std::string::npos)
            text[data.substr(0, nul)] = data.substr(nul + 1);
        if (type == "iTXt" && nul != std::string::npos) {
            // keyword NUL flag method language NUL translated-keyword NUL text
            const std::size_t lang_end = data.find('\0', nul + 3);
            const std::size_t translated_end = data.find('\0', lang_end + 1);
            text[data.substr(0, nul)] = data.substr(translated_end + 1);
        }
        if (type == "IEND") break;
        at += 12 + length;
    }
    return text;
}

}  // namespace tirpol::test
