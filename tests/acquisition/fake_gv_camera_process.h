#pragma once
// Starts Aravis's own fake GigE Vision camera (`arv-fake-gv-camera-0.8 -i 127.0.0.1`, package
// aravis-tools) as a child process and stops it on destruction. Only one GigE Vision device can
// listen on 127.0.0.1:3956, and CTest runs test cases in parallel processes, so the fixture holds
// an exclusive flock on a lock file for its lifetime. Used by the Aravis tests and the acquisition
// benchmark.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "tirpol/acquisition/internal/aravis_camera.h"

extern char** environ;

namespace tirpol::test {

inline constexpr const char* kFakeGvCameraBinary = "arv-fake-gv-camera-0.8";
/// Aravis's device id for the fake camera: "<vendor>-<model>-<serial>" with the default serial
/// GV01.
inline constexpr const char* kFakeGvCameraId = "Aravis-Fake-GV01";

/// Full path of `arv-fake-gv-camera-0.8` on PATH, or nullopt when aravis-tools is not installed.
inline std::optional<std::filesystem::path> find_fake_gv_camera_binary() {
    const char* path = std::getenv("PATH");
    std::string dirs = path != nullptr ? path : "/usr/bin:/bin";
    std::size_t start = 0;
    while (start <= dirs.size()) {
        const std::size_t end = std::min(dirs.find(':', start), dirs.size());
        const std::filesystem::path candidate =
            std::filesystem::path(dirs.substr(start, end - start)) / kFakeGvCameraBinary;
        if (::access(candidate.c_str(), X_OK) == 0) return candidate;
        start = end + 1;
    }
    return std::nullopt;
}

/// Exclusive use of the loopback GigE Vision port, across processes.
class LoopbackGigELock {
public:
    LoopbackGigELock() {
        m_fd = ::open("/tmp/tirpol-loopback-gige.lock", O_RDWR | O_CREAT | O_CLOEXEC, 0666);
        if (m_fd >= 0) ::flock(m_fd, LOCK_EX);
    }
    ~LoopbackGigELock() {
        if (m_fd >= 0) ::close(m_fd);  // releases the flock
    }
    LoopbackGigELock(const LoopbackGigELock&) = delete;
    LoopbackGigELock& operator=(const LoopbackGigELock&) = delete;

private:
    int m_fd = -1;
};

class FakeGvCameraProcess {
public:
    /// Starts the binary with `-i 127.0.0.1` plus `extra_args` (e.g. {"-g", xml} or {"-r", "30"})
    /// and waits until the camera answers. `ready()` tells whether it did.
    FakeGvCameraProcess(const std::filesystem::path& binary,
                        const std::vector<std::string>& extra_args) {
        std::vector<std::string> args = {binary.string(), "-i", "127.0.0.1"};
        args.insert(args.end(), extra_args.begin(), extra_args.end());
        std::vector<char*> argv;
        for (auto& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        // The fake camera logs a critical per frame for pixel formats its test pattern lacks
        // (Mono14).
        posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
        if (posix_spawn(&m_pid, binary.c_str(), &actions, nullptr, argv.data(), environ) != 0)
            m_pid = -1;
        posix_spawn_file_actions_destroy(&actions);
        if (m_pid <= 0) return;
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while (std::chrono::steady_clock::now() < deadline) {
            auto camera = acquisition::open_aravis_camera("127.0.0.1");
            if (camera.ok()) {
                m_ready = true;
                return;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
    }
    ~FakeGvCameraProcess() {
        if (m_pid > 0) {
            ::kill(m_pid, SIGTERM);
            int status = 0;
            ::waitpid(m_pid, &status, 0);
        }
    }
    FakeGvCameraProcess(const FakeGvCameraProcess&) = delete;
    FakeGvCameraProcess& operator=(const FakeGvCameraProcess&) = delete;
    bool ready() const { return m_ready; }

private:
    pid_t m_pid = -1;
    bool m_ready = false;
};

}  // namespace tirpol::test
