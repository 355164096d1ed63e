#include "fuzz_support.h"

#include <unistd.h>

#include <fstream>

namespace tirpol::fuzz {

std::filesystem::path source_dir() { return TIRPOL_SOURCE_DIR; }

std::filesystem::path scratch_dir() {
    static const std::filesystem::path dir = [] {
        auto d =
            std::filesystem::temp_directory_path() / ("tirpol-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

std::filesystem::path write_input(const std::string& name, const std::uint8_t* data,
                                  std::size_t size) {
    const auto path = scratch_dir() / name;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return path;
}

}  // namespace tirpol::fuzz
