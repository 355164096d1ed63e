#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "tirpol/core/error.h"
#include "tirpol/core/output_guard.h"

namespace tirpol {

FolderLock::FolderLock(const std::filesystem::path& folder, const std::string& what)
    : m_path(folder / ".lock") {
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) fail("{}: cannot create the folder: {}", folder.string(), ec.message());
    m_fd = ::open(m_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (m_fd < 0)
        fail("{}: cannot create the lock file: {}", m_path.string(), std::strerror(errno));
    if (::flock(m_fd, LOCK_EX | LOCK_NB) != 0) {
        const int err = errno;
        char buffer[32] = {};
        const ssize_t n = ::pread(m_fd, buffer, sizeof buffer - 1, 0);
        ::close(m_fd);
        m_fd = -1;
        if (err != EWOULDBLOCK) fail("{}: cannot lock: {}", m_path.string(), std::strerror(err));
        std::string holder(buffer, n > 0 ? static_cast<std::size_t>(n) : 0);
        while (!holder.empty() && (holder.back() == '\n' || holder.back() == ' '))
            holder.pop_back();
        fail("{} is in use by {} ({} holds {}); wait for it to finish, or write to another folder",
             folder.string(), holder.empty() ? std::string("another process") : "process " + holder,
             what, m_path.string());
    }
    // Our pid, for the message of a run that finds the folder locked.
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(m_fd, 0) != 0 ||
        ::pwrite(m_fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
        // The lock holds without the pid; a refused run then says "another process".
    }
}

FolderLock::~FolderLock() {
    if (m_fd >= 0) ::close(m_fd);
}

}  // namespace tirpol
