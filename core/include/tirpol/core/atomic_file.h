#pragma once
/// \file atomic_file.h
/// Atomic writes: content goes to a temporary file in the destination directory, is flushed to
/// disk, then renamed over the destination. A reader never sees a half-written file; a failure
/// (full disk, permissions) leaves the old file untouched and throws tirpol::Error naming the path.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace tirpol {

/// The first atomic write into a folder by a process also removes the temporary files that killed
/// writes left there (remove_abandoned_temp_files).

/// The process id in the name of one of these temporary files (".<name>.tmp-<pid>-<random><ext>"),
/// or std::nullopt for any other name.
std::optional<long> temp_file_owner_pid(const std::string& file_name);

/// Removes from `folder` the temporary files of atomic writes that can no longer finish: named as
/// above, last written before this process started, and whose process is not running (a live pid
/// keeps its files: another run may be writing them). Returns how many were removed.
std::size_t remove_abandoned_temp_files(const std::filesystem::path& folder);

/// Writes `content` to `path` atomically.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

/// For writers that need a file name (OpenEXR, OpenCV): write to temp_path(), then commit().
/// If commit() is never called, the temporary file is removed.
class AtomicFile {
public:
    explicit AtomicFile(std::filesystem::path destination);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    const std::filesystem::path& temp_path() const { return m_temp; }
    /// fsyncs the temporary file and renames it over the destination.
    void commit();

private:
    std::filesystem::path m_destination;
    std::filesystem::path m_temp;
    bool m_committed = false;
};

/// Reads a whole file; throws tirpol::Error naming the path if it cannot be read.
std::string read_file(const std::filesystem::path& path);

}  // namespace tirpol
