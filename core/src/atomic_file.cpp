#include "tirpol/core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <random>
#include <set>

#include "output_claims.h"
#include "tirpol/core/error.h"

namespace tirpol {

namespace {
/// When this process started (static initialisation): a temporary file older than this was not made
/// by it.
const std::filesystem::file_time_type g_process_start =
    std::filesystem::file_time_type::clock::now();

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
    if (ec)
        fail("{}: cannot create directory '{}': {}", path.string(), path.parent_path().string(),
             ec.message());
}

/// Once per folder and process, on its first atomic write there.
void sweep_folder_once(const std::filesystem::path& folder) {
    static std::mutex mutex;
    static std::set<std::filesystem::path> swept;
    std::error_code ec;
    const auto key = std::filesystem::weakly_canonical(folder.empty() ? "." : folder, ec);
    {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!swept.insert(key).second) return;
    }
    remove_abandoned_temp_files(folder.empty() ? "." : folder);
}
}  // namespace

std::optional<long> temp_file_owner_pid(const std::string& name) {
    // ".<destination>.tmp-<pid>-<random><extension>", as temp_name_for makes them.
    if (name.size() < 8 || name.front() != '.') return std::nullopt;
    const auto tag = name.rfind(".tmp-");
    if (tag == std::string::npos || tag == 0) return std::nullopt;
    std::size_t i = tag + 5, pid_end = i;
    while (pid_end < name.size() && std::isdigit(static_cast<unsigned char>(name[pid_end])))
        ++pid_end;
    if (pid_end == i || pid_end - i > 9 || pid_end >= name.size() || name[pid_end] != '-')
        return std::nullopt;
    std::size_t random_end = pid_end + 1;
    while (random_end < name.size() && std::isdigit(static_cast<unsigned char>(name[random_end])))
        ++random_end;
    if (random_end == pid_end + 1) return std::nullopt;
    // What follows is the destination's extension, if any.
    const std::string rest = name.substr(random_end);
    if (!rest.empty() && (rest.front() != '.' || rest.find('/') != std::string::npos))
        return std::nullopt;
    return std::stol(name.substr(i, pid_end - i));
}

std::size_t remove_abandoned_temp_files(const std::filesystem::path& folder) {
    std::size_t removed = 0;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
        std::error_code e;
        if (!entry.is_regular_file(e)) continue;
        const auto pid = temp_file_owner_pid(entry.path().filename().string());
        if (!pid) continue;
        // Made before this process started, by a process that no longer runs (a pid in use by
        // another process keeps the file: it may be that writer's, still at work).
        const auto written = std::filesystem::last_write_time(entry.path(), e);
        if (e || written >= g_process_start) continue;
        const bool alive =
            *pid != ::getpid() && (::kill(static_cast<pid_t>(*pid), 0) == 0 || errno == EPERM);
        if (alive) continue;
        if (std::filesystem::remove(entry.path(), e)) ++removed;
    }
    return removed;
}

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
            fail("{}: write failed after {} of {} bytes: {}", path.string(), written,
                 content.size(), std::strerror(err));
        }
        written += static_cast<std::size_t>(n);
    }
    if (::close(fd) != 0)
        fail("{}: write failed on close: {}", path.string(), std::strerror(errno));
    file.commit();
}

AtomicFile::AtomicFile(std::filesystem::path destination) : m_destination(std::move(destination)) {
    detail::write_output_claims_before(m_destination);
    ensure_parent(m_destination);
    sweep_folder_once(m_destination.parent_path());
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
    if (ec)
        fail("{}: cannot move the finished file into place: {}", m_destination.string(),
             ec.message());
    m_committed = true;
}

}  // namespace tirpol
