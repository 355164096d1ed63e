#include "tirpol/core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>

#include "tirpol/core/error.h"

namespace tirpol {

namespace {
std::filesystem::path temp_name_for(const std::filesystem::path& destination) {
    static thread_local std::mt19937_64 rng{std::random_device{}()};
    auto name = "." + destination.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                std::to_string(rng() % 1000000007ULL);
    // Keep the extension: OpenEXR and OpenCV choose the format from it.
    return destination.parent_path() / (name + destination.extension().string());
}

void fsync_path(const std::filesystem::path& path) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd < 0) fail("{}: cannot reopen to flush: {}", path.string(), std::strerror(errno));
    const int rc = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    if (rc != 0) fail("{}: flushing to disk failed: {}", path.string(), std::strerror(err));
}

void ensure_parent(const std::filesystem::path& path) {
    if (!path.has_parent_path()) return;
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec) fail("{}: cannot create directory '{}': {}", path.string(), path.parent_path().string(), ec.message());
}
}  // namespace

void write_file_atomic(const std::filesystem::path& path, std::string_view content) {
    AtomicFile file(path);
    const int fd = ::open(file.temp_path().c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) fail("{}: cannot create: {}", path.string(), std::strerror(errno));
    std::size_t written = 0;
    while (written < content.size()) {
        const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
        if (n < 0) {
            if (errno == EINTR) continue;
            const int err = errno;
            ::close(fd);
            fail("{}: write failed after {} of {} bytes: {}", path.string(), written, content.size(),
                 std::strerror(err));
        }
        written += static_cast<std::size_t>(n);
    }
    if (::close(fd) != 0) fail("{}: write failed on close: {}", path.string(), std::strerror(errno));
    file.commit();
}

AtomicFile::AtomicFile(std::filesystem::path destination) : m_destination(std::move(destination)) {
    ensure_parent(m_destination);
    m_temp = temp_name_for(m_destination);
}

AtomicFile::~AtomicFile() {
    if (!m_committed) {
        std::error_code ec;
        std::filesystem::remove(m_temp, ec);
    }
}

void AtomicFile::commit() {
    fsync_path(m_temp);
    std::error_code ec;
    std::filesystem::rename(m_temp, m_destination, ec);
    if (ec) fail("{}: cannot move the finished file into place: {}", m_destination.string(), ec.message());
    m_committed = true;
}

}  // namespace tirpol
