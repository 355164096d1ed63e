#pragma once
/// \file emissivity_cache.h
/// Emissivity tables (emissivity.h) cached in memory for the life of the process and on disk across
/// processes. A table is keyed by what determines it: the model name, its parameters (n, k, σ, …)
/// at every wavelength of the table, the wavelengths themselves (the spectral grid of a band), the
/// angle grid, the integrator options and kEmissivityCacheVersion. So editing a material file or
/// choosing another band or grid selects another entry; nothing is ever looked up by name alone.
///
/// Disk entries live in one folder, one file per table (`<model>-<128-bit key>.emtab`), written
/// atomically (core atomic_file.h). A file is trusted only if its magic, version, key, wavelengths,
/// sizes, finite values and checksum all match; otherwise it is rebuilt and overwritten. A folder
/// that cannot be written only costs the rebuild (a warning is logged), never a failed render.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/pbrdf.h"

namespace tirpol::materials {

/// Bump when the emissivity integrator or a model's sampling changes the numbers a table holds.
inline constexpr int kEmissivityCacheVersion = 1;

/// Where a cached table came from.
enum class EmissivityCacheSource {
    memory,           ///< already built or loaded by this process
    disk,             ///< read from a valid cache file
    built,            ///< computed (no cache file, or no cache folder)
    rebuilt_corrupt,  ///< computed because the cache file was invalid; the file was replaced
};

struct CachedEmissivityTable {
    std::shared_ptr<const EmissivityTable> table;
    EmissivityCacheSource source = EmissivityCacheSource::built;
};

/// The disk cache folder: $TIRPOL_CACHE_DIR if set, else $XDG_CACHE_HOME/tirpol (absolute paths
/// only, per the XDG base-directory specification), else $HOME/.cache/tirpol; empty if none
/// applies.
std::filesystem::path default_emissivity_cache_directory();

/// Hex key of the table `EmissivityTable(brdf, wavelengths_um, angle_nodes, options)` would hold
/// (file comment). Deterministic across processes and machines of the same endianness.
std::string emissivity_table_key(const PolarizedBrdf& brdf,
                                 const std::vector<double>& wavelengths_um, int angle_nodes = 65,
                                 const EmissivityOptions& options = {});

/// The table for `brdf` at `wavelengths_um`: from this process's memory, else from `directory`,
/// else built (and stored in both). An empty `directory` keeps the cache in memory only.
/// Thread-safe. Throws what EmissivityTable's constructor throws.
CachedEmissivityTable cached_emissivity_table(const PolarizedBrdf& brdf,
                                              const std::vector<double>& wavelengths_um,
                                              const std::filesystem::path& directory,
                                              int angle_nodes = 65,
                                              const EmissivityOptions& options = {});

/// Forgets every table held in memory (tests; long-running processes that reload materials need not
/// call it, since a changed material has another key).
void clear_emissivity_memory_cache();

}  // namespace tirpol::materials
