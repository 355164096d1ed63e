#pragma once
/// \file folder_lock.h
/// One writer per output folder: an exclusive flock(2) on FOLDER/.lock for as long as the object
/// lives. The kernel releases it when the process ends, even by SIGKILL, so a crashed run never
/// leaves the folder locked. The holder writes its pid into the file, so a refused second run can
/// name it.

#include <filesystem>
#include <string>

namespace tirpol {

class FolderLock {
public:
    /// Creates `folder` if needed and locks it. Throws tirpol::Error naming the folder and the pid
    /// of the process that holds it ("… is in use by process 1234 (a tirpol sweep?) …", `what`
    /// filling in the kind of run) when another process has it.
    FolderLock(const std::filesystem::path& folder, const std::string& what);
    ~FolderLock();
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;

    /// The lock file, FOLDER/.lock.
    const std::filesystem::path& path() const { return m_path; }

private:
    std::filesystem::path m_path;
    int m_fd = -1;
};

}  // namespace tirpol
