#pragma once
/// \file limits.h
/// Resource limits and physical ranges that every reader, library function and command-line option
/// checks before it allocates or accepts a value. One table, so that a limit is raised (or
/// explained) once; docs/cli.md lists it for users.
///
/// Range checks shared by every reader and command, so that one quantity is held to one range
/// (limits.h) with one wording. Each throws tirpol::Error naming `what` (a field, flag or column).
///
/// A value a user gave for a command-line option that the library found wrong once it had read the
/// files the value refers to (a time in a site's offset, a name in a file's list). The CLI exits
/// 2 with it, as a usage error naming the option, instead of 1 for a bad input file. And the one
/// parser of numbers in option values, with the table of option ranges (docs/cli.md lists it).
///
/// Checking a job's memory estimate against what the machine has, before allocating: a render or
/// a table that cannot fit is refused with its estimate instead of ending in std::bad_alloc, the
/// OOM killer or swap.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "tirpol/core/error.h"

namespace tirpol::limits {

/// Largest image side tirpol reads or creates, pixels (thermal cameras are ≤ 1280; renders ≤ 8K).
inline constexpr int kMaxImageSide = 16384;
/// Largest image area, pixels (8192² ≈ 67 M: 268 MB per float channel).
inline constexpr std::size_t kMaxImagePixels = std::size_t{1} << 26;
/// Largest decoded-size-to-file-size ratio accepted for a compressed image. zlib cannot exceed
/// ~1032:1, RLE 64:1; a header declaring more pixels than this is a lie, not an image.
inline constexpr double kMaxCompressionRatio = 4096.0;
/// Data rows accepted in a CSV input (a spectrum, an emissivity table, a weather series).
inline constexpr std::size_t kMaxCsvRows = 1'000'000;

/// Largest text input (JSON manifest, YAML config, CSV table) read into memory, bytes. The largest
/// real ones (an hourly EPW year, a 1 M-row spectrum) are ≈ 40 MB; beyond this a file is refused
/// before it is read, and a read never goes further (a device that streams for ever).
inline constexpr std::uintmax_t kMaxTextFileBytes = std::uintmax_t{256} << 20;

/// Largest image file (EXR, PNG, TIFF) opened, bytes: a 16384² float image with four channels is 4
/// GiB uncompressed; the pixel-count limits above bound what is decoded.
inline constexpr std::uintmax_t kMaxImageFileBytes = std::uintmax_t{4} << 30;

/// Physical temperature range accepted for any temperature in a file or on the command line, K.
inline constexpr double kMinTemperatureK = 1.0;
inline constexpr double kMaxTemperatureK = 10000.0;

/// Measured emissivities may stray outside [0, 1] by noise; beyond this tolerance they are errors.
inline constexpr double kEmissivityTolerance = 0.05;
/// Smallest emissivity an emissivity correction divides by (FLIR's object-signal inversion): below
/// it the reflected term dominates and 1/ε amplifies a count of noise into kelvins of error (ε =
/// 0.01 gives 100 counts per count); FLIR's cameras offer the same range (data sheets: "emissivity
/// correction variable from 0.01 to 1.0").
inline constexpr double kMinCorrectionEmissivity = 0.01;

/// Wavelength range of any band or wavelength, µm: 0.1 µm (far UV, below which no thermal source
/// of ≤ 10000 K emits a measurable fraction) to 1000 µm (the end of the far infrared).
inline constexpr double kMinWavelengthUm = 0.1;
inline constexpr double kMaxWavelengthUm = 1000.0;
/// Quadrature nodes of one band (16 per 0.25 µm panel, plus the RSR's knots): the whole
/// 0.1–1000 µm range at the finest panel is ≈ 64 000 nodes; an RSR with a million knots is not.
inline constexpr std::size_t kMaxBandNodes = std::size_t{1} << 20;

/// Samples per pixel of a render (the project's reference renders use ≤ 4096).
inline constexpr int kMaxSamplesPerPixel = 1 << 20;
/// Multi-start count of a fit (each start is a full Ceres solve; 16 is the default, 1000 already
/// takes minutes).
inline constexpr int kMaxFitStarts = 10000;
/// Frames averaged or captured per step and repeats of a plan or command.
inline constexpr int kMaxFramesPerStep = 100000;

/// Fraction of the memory the kernel reports available (MemAvailable) that one job may plan to
/// use: the rest is left to the page cache and the other processes.
inline constexpr double kMaxMemoryFraction = 0.8;

}  // namespace tirpol::limits

namespace tirpol {

/// `temperature_k` if it lies in [limits::kMinTemperatureK, limits::kMaxTemperatureK].
double check_temperature_k(double temperature_k, std::string_view what);

/// `value` if it is finite: a computed result that overflowed is an error, never printed as
/// inf/nan.
double check_finite(double value, std::string_view what);

/// `value` if it is finite and ≥ 0 (an uncertainty, a noise level, a duration).
double check_non_negative(double value, std::string_view what);

class OptionValueError : public Error {
public:
    /// `message` may begin with `option` already; the CLI then prints it once.
    OptionValueError(std::string option, const std::string& message)
        : Error(message), m_option(std::move(option)) {}
    /// The option ("--at").
    const std::string& option() const { return m_option; }

private:
    std::string m_option;
};

/// `parse()` of an option's text by a library function (a pattern, a method name, angles), with its
/// tirpol::Error rethrown as an OptionValueError naming `option`: the value is wrong, not a file or
/// a device, so the CLI exits 2 with it as a usage error.
template <typename Parse>
auto parse_option_value(const std::string& option, Parse&& parse) -> decltype(parse()) {
    try {
        return parse();
    } catch (const Error& e) {
        throw OptionValueError(option, e.what());
    }
}

/// All of `text` as one number in strtod's syntax (as CLI11 converts option values), or nullopt
/// when `text` is empty or not all number. A value beyond a double's range is ±inf.
std::optional<double> parse_number(std::string_view text);

/// The range [lo, hi] the limits table (from core/limits.h) gives an option's values.
struct OptionLimit {
    double lo, hi;
    std::string why;  ///< what the range is, for the message
};

/// The limit of option `long_name` ("--band-um") in subcommand `subcommand` ("planck", "calibrate
/// radiometric"), or of that option in every subcommand, or nullptr.
const OptionLimit* option_limit(const std::string& subcommand, const std::string& long_name);

/// Why `text` is refused as a value of a numeric option with `limit` (nullptr: none): not finite,
/// or outside the limit. Empty when it is accepted, and when it is no number at all (the option
/// parser reports that itself).
std::string option_number_problem(const std::string& text, const OptionLimit* limit);

/// MemAvailable from /proc/meminfo, bytes (the kernel's estimate of what can be allocated without
/// swapping); nullopt where it cannot be read (not Linux).
std::optional<std::uint64_t> available_memory_bytes();

/// Throws tirpol::Error "<what>: needs an estimated N GiB of memory, more than the M GiB available
/// (limits::kMaxMemoryFraction of MemAvailable)" when `estimate_bytes` exceeds that budget.
/// `available_bytes` stands in for available_memory_bytes() (tests); without either, no check.
void check_memory_estimate(std::uint64_t estimate_bytes, std::string_view what,
                           std::optional<std::uint64_t> available_bytes = available_memory_bytes());

}  // namespace tirpol
