#pragma once
/// \file fuzz_support.h
/// What every fuzz target shares: the input as a file (most parsers read paths, and their messages
/// name them) and the rule that a parser may reject input only with tirpol::Error. Any other
/// exception (std::bad_alloc, a json type_error, ...) escapes and is reported as a crash.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "tirpol/core/error.h"

namespace tirpol::fuzz {

/// The input bytes as text.
inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

/// The source tree (config/ for targets whose inputs name shipped files).
std::filesystem::path source_dir();

/// A per-process scratch directory (created once, reused by every input so no file system churn).
std::filesystem::path scratch_dir();

/// Writes the input to scratch_dir()/name and returns that path.
std::filesystem::path write_input(const std::string& name, const std::uint8_t* data,
                                  std::size_t size);

/// Runs `parse`; tirpol::Error is the expected way to reject input, anything else propagates.
template <typename F>
void expect_clean_rejection(F&& parse) {
    try {
        parse();
    } catch (const tirpol::Error&) {
    }
}

}  // namespace tirpol::fuzz
