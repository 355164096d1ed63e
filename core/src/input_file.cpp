#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/output_guard.h"

namespace tirpol {

namespace {
const char* kind_of(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

std::string size_text(std::uintmax_t bytes) {
    if (bytes >= (std::uintmax_t{1} << 20))
        return fmt::format("{:.1f} MiB", static_cast<double>(bytes) / (1 << 20));
    return fmt::format("{} bytes", bytes);
}

void check_stat(const std::filesystem::path& path, const struct stat& st,
                std::uintmax_t max_bytes) {
    if (!S_ISREG(st.st_mode))
        fail("{}: is {}; tirpol reads inputs only from regular files", path.string(),
             kind_of(st.st_mode));
    if (static_cast<std::uintmax_t>(st.st_size) > max_bytes)
        fail("{}: {} is larger than the {} tirpol reads from an input of this kind (limits.h)",
             path.string(), size_text(static_cast<std::uintmax_t>(st.st_size)),
             size_text(max_bytes));
}

[[noreturn]] void fail_errno(const std::filesystem::path& path, int err) {
    if (err == ENOENT) fail("{}: no such file (cannot open it for reading)", path.string());
    fail("{}: cannot open for reading: {}", path.string(), std::strerror(err));
}

struct Descriptor {
    int fd;
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
};
}  // namespace

void check_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) fail_errno(path, errno);
    check_stat(path, st, max_bytes);
}

std::string read_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes) {
    const Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (file.fd < 0) fail_errno(path, errno);
    struct stat st {};
    if (::fstat(file.fd, &st) != 0) fail_errno(path, errno);
    check_stat(path, st, max_bytes);
    std::string text;
    text.resize(static_cast<std::size_t>(st.st_size));
    std::size_t used = 0;
    // The file may grow after fstat: read until end of file, but never past max_bytes + 1.
    for (;;) {
        if (used == text.size()) {
            if (text.size() > max_bytes) break;
            text.resize(std::min<std::size_t>(static_cast<std::size_t>(max_bytes) + 1,
                                              std::max<std::size_t>(4096, 2 * text.size())));
        }
        const ssize_t n = ::read(file.fd, text.data() + used, text.size() - used);
        if (n < 0) {
            if (errno == EINTR) continue;
            fail("{}: read failed after {} bytes: {}", path.string(), used, std::strerror(errno));
        }
        if (n == 0) break;
        used += static_cast<std::size_t>(n);
    }
    if (used > max_bytes)
        fail("{}: grew past the {} tirpol reads from an input of this kind while it was read",
             path.string(), size_text(max_bytes));
    text.resize(used);
    return text;
}

std::string read_file(const std::filesystem::path& path) {
    return read_input_file(path, limits::kMaxTextFileBytes);
}

}  // namespace tirpol
