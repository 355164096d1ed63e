#pragma once
// Helpers shared by every test suite: where the source tree is, and scratch directories that clean
// up.

#include <filesystem>
#include <string>

namespace tirpol::test {

/// Absolute path of the repository root (for config/ and tests/data/).
std::filesystem::path source_dir();

/// A fresh empty directory under the system temp dir, removed when the object goes out of scope.
class TempDir {
public:
    explicit TempDir(const std::string& prefix = "tirpol-test");
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return m_path; }
    std::filesystem::path operator/(const std::string& name) const { return m_path / name; }

private:
    std::filesystem::path m_path;
};

/// Writes `text` to `path` (creating parent directories).
void write_text(const std::filesystem::path& path, const std::string& text);

}  // namespace tirpol::test
