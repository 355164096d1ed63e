#pragma once
/// \file output_guard.h
/// A command's outputs checked against its inputs before any work starts (docs/cli.md, "Outputs
/// never replace inputs"). Every writing subcommand of the CLI lists what it reads and what it will
/// write, then calls check(): paths are resolved (symlinks followed, `..` removed) and files are
/// also compared by device and inode, so a hard link or another spelling of an input is caught.
///
/// Refused, whatever --force says: an output that is one of the inputs, an output inside an input
/// folder (a session), an input inside a folder output under a name the command writes, two outputs
/// on one path, an output whose path goes through an existing non-folder (`-o afile/x`), a folder
/// output that exists as a file or a file output that exists as a folder. Refused unless `force`:
/// an existing file at a file output; in a folder output, an existing entry the command would write
/// (a name matching one of its patterns) that no tirpol command claimed there before. A folder
/// output keeps every entry it does not claim; what a command claims in a folder is listed in the
/// folder's `.tirpol-outputs` (one pattern a line), so a re-run into its own folder (render, sweep
/// --resume, compare, demo) is not refused.
///
/// One writer per output folder: an exclusive flock(2) on FOLDER/.lock for as long as the object
/// lives. The kernel releases it when the process ends, even by SIGKILL, so a crashed run never
/// leaves the folder locked. The holder writes its pid into the file, so a refused second run can
/// name it.
///
/// Opening what a user names as an input: only a regular file is read (a FIFO would block the open
/// or the read for ever, /dev/zero or /dev/urandom never end), and never more than a limit
/// (limits::kMaxTextFileBytes for text). Errors name the path and what was found.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"

namespace tirpol {

/// An output that would replace or mix with an input or an existing file; the CLI exits 2 with it.
class OutputConflict : public Error {
public:
    OutputConflict(std::string option, const std::string& message)
        : Error(message), m_option(std::move(option)) {}
    /// The command-line option of the output ("--output", "--csv", …).
    const std::string& option() const { return m_option; }

private:
    std::string m_option;
};

/// The name of the ledger a folder output keeps of the patterns tirpol commands claimed in it.
inline constexpr const char* kOutputLedgerName = ".tirpol-outputs";

class OutputGuard {
public:
    /// A file or folder the command reads; `what` names it in messages ("SESSION",
    /// "--calibration"). An empty path is ignored (an option not given).
    OutputGuard& input(const std::filesystem::path& path, std::string what);
    /// A file the command writes (atomically, replacing any file there).
    OutputGuard& output_file(const std::filesystem::path& path, std::string option);
    /// A folder the command writes into: `patterns` (fnmatch, top-level names: "report.html",
    /// "*_S0.png", "points") are what it may create or replace there; other entries are kept.
    OutputGuard& output_folder(const std::filesystem::path& path, std::string option,
                               std::vector<std::string> patterns);
    /// A folder whose own writer decides what may exist in it (a capture session: SessionWriter
    /// refuses a non-empty folder unless resuming); checked against the inputs only.
    OutputGuard& output_session(const std::filesystem::path& path, std::string option);

    /// Throws OutputConflict naming the output, its option and the input or existing file (both
    /// paths) for the first conflict found; see the file comment for what `force` allows. Writes
    /// nothing: a folder output's patterns go into its ledger just before the first atomic write
    /// under it (write_file_atomic, AtomicFile), so a command that stops on a bad input leaves no
    /// trace.
    void check(bool force) const;

private:
    struct Input {
        std::filesystem::path path;
        std::string what;
    };
    enum class Kind { File, Folder, Session };
    struct Output {
        std::filesystem::path path;
        std::string option;
        Kind kind;
        std::vector<std::string> patterns;
    };
    std::vector<Input> m_inputs;
    std::vector<Output> m_outputs;
};

/// `path` with symlinks resolved as far as it exists and the rest appended, made absolute and
/// normal (std::filesystem::weakly_canonical of the absolute path).
std::filesystem::path resolved_path(const std::filesystem::path& path);

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

/// Throws tirpol::Error unless `path` is a regular file (symbolic links followed) of at most
/// `max_bytes`: a missing file, a directory, a FIFO, a device or a socket is named as such. For
/// readers that hand the path to a library that opens it (OpenEXR, libpng, std::ifstream).
void check_input_file(const std::filesystem::path& path,
                      std::uintmax_t max_bytes = limits::kMaxTextFileBytes);

/// Reads a whole regular file of at most `max_bytes`. It is opened without blocking (O_NONBLOCK, so
/// a FIFO swapped in after the check cannot stall the open) and checked on the open descriptor;
/// the read stops at max_bytes + 1 whatever the file claims. Throws tirpol::Error naming the path.
/// (read_file() in atomic_file.h is this with limits::kMaxTextFileBytes.)
std::string read_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes);

/// Offset of the first byte of `text` that is not part of well-formed UTF-8 (RFC 3629), or npos.
std::size_t first_invalid_utf8(std::string_view text);

/// Throws tirpol::Error "<source>:<line>:<column>: invalid UTF-8 (byte 0xNN) ..." unless `text` is
/// well-formed UTF-8: YAML and JSON inputs are text, and a stray Latin-1 byte is named where it is
/// instead of surfacing later as a parser's type error.
void check_utf8_text(std::string_view text, std::string_view source);

}  // namespace tirpol
