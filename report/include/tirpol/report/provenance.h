#pragma once
/// \file provenance.h
/// What a comparison was made from, so a reader can cite it and repeat it: the tool version and
/// command line, and each input file with its SHA-256 (FIPS 180-4) and the header attributes it
/// carries (band, spp, seed, capture time, calibration files, scene and material parameters —
/// whatever the writer put there).

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tirpol/core/image.h"

namespace tirpol::report {

struct InputFile {
    std::string role;  ///< "measured", "simulated", "regions", "control points"
    std::filesystem::path path;
    std::string sha256;  ///< lower-case hex
    std::uintmax_t size_bytes = 0;
    /// Header attributes as (name, text) in name order; empty for non-EXR inputs.
    std::vector<std::pair<std::string, std::string>> attributes;
};

/// The git commit this library was configured from ("<40 hex digits>", with "-dirty" when tracked
/// files differed from it at configure time), or "not a git build" (built from a tarball or without
/// git). Read at configure time (cmake/BuildCommit.cmake), without network.
std::string build_commit();

struct Provenance {
    std::string tool_version;  ///< e.g. "tirpol 0.1.0"; empty when the caller is not the CLI
    std::string build_commit = report::build_commit();  ///< of the library that wrote the report
    std::string command_line;  ///< as typed, shell-quoted where needed; empty when not from the CLI
    std::vector<InputFile> inputs;
};

/// SHA-256 of `bytes` as 64 lower-case hex digits (FIPS 180-4).
std::string sha256_hex(std::string_view bytes);

/// The input file `path` with its checksum and size; `header` (when not null) supplies the
/// attributes. Throws tirpol::Error naming the file when it cannot be read.
InputFile describe_input(const std::string& role, const std::filesystem::path& path,
                         const Image* header = nullptr);

/// `file` relative to the directory `dir` (both made absolute against the current directory, with
/// symbolic links of their existing parts resolved), e.g. "../measured/view0.exr" for a report
/// directory beside "measured/"; the absolute path when no relative one exists (another root).
std::filesystem::path path_relative_to(const std::filesystem::path& file,
                                       const std::filesystem::path& dir);

/// An attribute value as text: strings as they are, numbers with up to 10 significant digits, lists
/// in [a, b].
std::string attribute_text(const AttributeValue& value);

/// argv joined by spaces, each argument single-quoted when it holds characters a POSIX shell would
/// interpret, so the line can be pasted back.
std::string quoted_command_line(int argc, const char* const* argv);

}  // namespace tirpol::report
