#pragma once
/// \file input_file.h
/// Opening what a user names as an input: only a regular file is read (a FIFO would block the open
/// or the read for ever, /dev/zero or /dev/urandom never end), and never more than a limit
/// (limits::kMaxTextFileBytes for text). Errors name the path and what was found.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "tirpol/core/limits.h"

namespace tirpol {

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
