#include "tirpol/core/output_guard.h"

#include <fmt/format.h>
#include <fnmatch.h>
#include <sys/stat.h>

#include <algorithm>
#include <mutex>
#include <optional>
#include <sstream>

#include "output_claims.h"
#include "tirpol/core/atomic_file.h"

namespace tirpol {

namespace fs = std::filesystem;

namespace {

struct FileId {
    dev_t device;
    ino_t inode;
    bool directory;
};

std::optional<FileId> file_id(const fs::path& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return std::nullopt;
    return FileId{st.st_dev, st.st_ino, S_ISDIR(st.st_mode)};
}

bool same_file(const std::optional<FileId>& a, const std::optional<FileId>& b) {
    return a && b && a->device == b->device && a->inode == b->inode;
}

/// Whether `inner` is `outer` or lies below it (both resolved).
bool is_within(const fs::path& inner, const fs::path& outer) {
    auto i = inner.begin();
    for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
        if (o->empty()) continue;  // a trailing separator
        if (i == inner.end() || *i != *o) return false;
    }
    return true;
}

bool matches_any(const std::string& name, const std::vector<std::string>& patterns) {
    for (const auto& p : patterns)
        if (::fnmatch(p.c_str(), name.c_str(), FNM_PERIOD) == 0) return true;
    return false;
}

std::vector<std::string> read_ledger(const fs::path& folder) {
    std::vector<std::string> patterns;
    std::error_code ec;
    if (!fs::is_regular_file(folder / kOutputLedgerName, ec)) return patterns;
    std::istringstream lines(read_file(folder / kOutputLedgerName));
    for (std::string line; std::getline(lines, line);)
        if (!line.empty() && line.front() != '#') patterns.push_back(line);
    return patterns;
}

/// Folder outputs whose check passed, waiting for their first file: their ledger is written then,
/// so a command that fails before writing anything leaves no trace (not even the folder).
struct PendingClaims {
    std::mutex mutex;
    std::vector<std::pair<fs::path, std::vector<std::string>>> folders;
};
PendingClaims& pending_claims() {
    static PendingClaims claims;
    return claims;
}

void write_ledger(const fs::path& folder, const std::vector<std::string>& claimed) {
    std::vector<std::string> patterns = read_ledger(folder);
    const std::size_t before = patterns.size();
    for (const auto& p : claimed)
        if (std::find(patterns.begin(), patterns.end(), p) == patterns.end()) patterns.push_back(p);
    if (patterns.size() == before && fs::exists(folder / kOutputLedgerName)) return;
    std::string text =
        "# names tirpol commands write in this folder (docs/cli.md); other entries are kept\n";
    for (const auto& p : patterns) text += p + "\n";
    write_file_atomic(folder / kOutputLedgerName, text);
}

}  // namespace

fs::path resolved_path(const fs::path& path) {
    std::error_code ec;
    fs::path absolute = fs::absolute(path, ec);
    if (ec) absolute = path;
    fs::path resolved = fs::weakly_canonical(absolute, ec);
    if (ec) resolved = absolute.lexically_normal();
    // "dir/" and "dir" are the same folder.
    if (!resolved.has_filename() && resolved.has_parent_path() && resolved != resolved.root_path())
        resolved = resolved.parent_path();
    return resolved;
}

OutputGuard& OutputGuard::input(const fs::path& path, std::string what) {
    if (!path.empty()) m_inputs.push_back({path, std::move(what)});
    return *this;
}

OutputGuard& OutputGuard::output_file(const fs::path& path, std::string option) {
    if (!path.empty()) m_outputs.push_back({path, std::move(option), Kind::File, {}});
    return *this;
}

OutputGuard& OutputGuard::output_folder(const fs::path& path, std::string option,
                                        std::vector<std::string> patterns) {
    if (!path.empty())
        m_outputs.push_back({path, std::move(option), Kind::Folder, std::move(patterns)});
    return *this;
}

OutputGuard& OutputGuard::output_session(const fs::path& path, std::string option) {
    if (!path.empty()) m_outputs.push_back({path, std::move(option), Kind::Session, {}});
    return *this;
}

void OutputGuard::check(bool force) const {
    struct ResolvedInput {
        const Input* input;
        fs::path path;
        std::optional<FileId> id;
    };
    std::vector<ResolvedInput> inputs;
    for (const auto& in : m_inputs)
        inputs.push_back({&in, resolved_path(in.path), file_id(in.path)});

    const auto conflict = [](const Output& out, const std::string& problem) {
        throw OutputConflict(out.option,
                             fmt::format("{} {}: {}", out.option, out.path.string(), problem));
    };
    const auto force_hint = "; pass --force to replace it, or choose another output";

    std::vector<std::pair<fs::path, const Output*>> seen;
    for (const Output& out : m_outputs) {
        const fs::path resolved = resolved_path(out.path);
        const auto id = file_id(resolved);
        std::error_code ec;

        for (const auto& [other, other_out] : seen) {
            const auto under = [](const fs::path& file, const fs::path& folder,
                                  const Output& folder_out) {
                return folder_out.kind == Kind::Folder && file != folder &&
                       is_within(file, folder) &&
                       matches_any(file.lexically_relative(folder).begin()->string(),
                                   folder_out.patterns);
            };
            if (other == resolved || under(resolved, other, *other_out) ||
                under(other, resolved, out))
                conflict(out,
                         fmt::format("is also written as {} ({}); each output needs its own path",
                                     other_out->option, other_out->path.string()));
        }
        seen.emplace_back(resolved, &out);

        // Every existing folder on the way must be a folder, or the write fails after the work.
        for (fs::path p = resolved.parent_path(); !p.empty(); p = p.parent_path()) {
            if (fs::exists(p, ec)) {
                if (!fs::is_directory(p, ec))
                    conflict(out, fmt::format("{} is not a folder", p.string()));
                break;
            }
            if (p == p.root_path()) break;
        }

        for (const auto& in : inputs) {
            if (resolved == in.path || same_file(id, in.id))
                conflict(
                    out,
                    fmt::format(
                        "is the input {} ({}); an output never replaces an input of its command",
                        in.input->what, in.input->path.string()));
            if (in.id && in.id->directory && is_within(resolved, in.path))
                conflict(out, fmt::format("lies inside the input folder {} ({}); write outside it",
                                          in.input->what, in.input->path.string()));
        }

        if (out.kind == Kind::File) {
            if (id && id->directory) conflict(out, "is a folder; expected a file name");
            if (id && !force)
                conflict(out, fmt::format("exists and was not written by this run{}", force_hint));
            continue;
        }
        if (id && !id->directory) conflict(out, "exists and is not a folder");
        if (out.kind == Kind::Session || !id) continue;

        // A folder output: inputs inside it must not be under a name it writes; existing entries it
        // would write must have been claimed by tirpol before (the ledger) or be allowed by
        // --force.
        for (const auto& in : inputs) {
            if (!is_within(in.path, resolved) || in.path == resolved) continue;
            const std::string top = in.path.lexically_relative(resolved).begin()->string();
            if (matches_any(top, out.patterns))
                conflict(
                    out,
                    fmt::format(
                        "would write {} over the input {} ({}); an output never replaces an input",
                        (out.path / top).string(), in.input->what, in.input->path.string()));
        }
        const std::vector<std::string> owned = read_ledger(resolved);
        for (const auto& entry : fs::directory_iterator(resolved, ec)) {
            const std::string name = entry.path().filename().string();
            if (!matches_any(name, out.patterns)) continue;
            const fs::path shown = out.path / name;
            const auto entry_id = file_id(entry.path());
            for (const auto& in : inputs)
                if (same_file(entry_id, in.id))
                    conflict(out,
                             fmt::format("would write {}, which is the input {} ({})",
                                         shown.string(), in.input->what, in.input->path.string()));
            if (!force && !matches_any(name, owned))
                conflict(
                    out,
                    fmt::format(
                        "holds {}, which this command would replace and no tirpol command wrote{}",
                        shown.string(), force_hint));
        }
    }
    auto& pending = pending_claims();
    const std::lock_guard<std::mutex> lock(pending.mutex);
    for (const Output& out : m_outputs)
        if (out.kind == Kind::Folder)
            pending.folders.emplace_back(resolved_path(out.path), out.patterns);
}

namespace detail {
void write_output_claims_before(const fs::path& destination) {
    auto& pending = pending_claims();
    std::vector<std::pair<fs::path, std::vector<std::string>>> due;
    {
        const std::lock_guard<std::mutex> lock(pending.mutex);
        if (pending.folders.empty()) return;
        const fs::path resolved = resolved_path(destination);
        for (auto it = pending.folders.begin(); it != pending.folders.end();) {
            if (is_within(resolved, it->first) && resolved != it->first) {
                due.push_back(std::move(*it));
                it = pending.folders.erase(it);
            } else {
                ++it;
            }
        }
    }
    // Outside the lock: the ledger is itself written atomically (and comes back here, with nothing
    // due).
    for (const auto& [folder, patterns] : due) write_ledger(folder, patterns);
}
}  // namespace detail

}  // namespace tirpol
