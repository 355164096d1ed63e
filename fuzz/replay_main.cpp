// Replays files through a fuzz target's LLVMFuzzerTestOneInput without libFuzzer, so every build
// (g++ included) checks that the kept crashers and the seed corpus are still handled cleanly.
// Usage: <target>_replay FILE_OR_DIR...   Exits non-zero if no input was found (a missing corpus
// must not pass silently); a crash aborts the process, which fails the ctest test.

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {
void replay(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    std::printf("replay %s (%zu bytes)\n", file.c_str(), bytes.size());
    std::fflush(stdout);
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}
}  // namespace

int main(int argc, char** argv) {
    std::size_t count = 0;
    for (int i = 1; i < argc; ++i) {
        const std::filesystem::path arg(argv[i]);
        if (std::filesystem::is_directory(arg)) {
            std::vector<std::filesystem::path> files;
            for (const auto& e : std::filesystem::recursive_directory_iterator(arg))
                if (e.is_regular_file() && e.path().filename() != ".keep")
                    files.push_back(e.path());
            std::sort(files.begin(), files.end());
            for (const auto& f : files) replay(f), ++count;
        } else if (std::filesystem::is_regular_file(arg)) {
            replay(arg), ++count;
        }
    }
    if (count == 0) {
        std::fprintf(stderr, "no inputs found in the paths given\n");
        return 1;
    }
    std::printf("%zu inputs replayed cleanly\n", count);
    return 0;
}
