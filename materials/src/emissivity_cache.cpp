#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <string_view>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/materials/emissivity.h"

namespace tirpol::materials {

namespace {

constexpr std::string_view kMagic = "tirpol-emtab\n";

/// FNV-1a, 64 bit (Fowler, Noll, Vo); two offset bases give the 128-bit key and an independent
/// checksum.
std::uint64_t fnv1a(std::string_view bytes, std::uint64_t basis = 0xcbf29ce484222325ULL) {
    std::uint64_t h = basis;
    for (const char c : bytes) {
        h ^= static_cast<unsigned char>(c);
        h *= 0x100000001b3ULL;
    }
    return h;
}
constexpr std::uint64_t kSecondBasis = 0x84222325cbf29ce4ULL;

/// Everything that determines a table's values, as text (hex floats: exact).
std::string key_text(const PolarizedBrdf& brdf, const std::vector<double>& wavelengths_um,
                     int angle_nodes, const EmissivityOptions& options) {
    const auto [lo, hi] = brdf.valid_wavelength_range_um();
    std::string text = fmt::format(
        "tirpol emissivity table v{}\nmodel {}\nrange {:a} {:a}\nangles {}\nquadrature {} {} {}\n",
        kEmissivityCacheVersion, brdf.model(), lo, hi, angle_nodes, options.radial_panels,
        options.azimuth_panels, options.order);
    text += fmt::format("delta {} {} isotropic {}\n", brdf.has_delta(), brdf.is_pure_delta(),
                        brdf.is_isotropic());
    for (const double w : wavelengths_um) {
        text += fmt::format("{:a}", w);
        for (const BrdfParameter& p : brdf.parameters(w))
            text += fmt::format(" {}={:a}", p.name, p.value);
        text += '\n';
    }
    return text;
}

template <typename T>
void append(std::string& out, const T& value) {
    out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <typename T>
bool take(std::string_view& in, T& value) {
    if (in.size() < sizeof(T)) return false;
    std::memcpy(&value, in.data(), sizeof(T));
    in.remove_prefix(sizeof(T));
    return true;
}

std::string serialize(const EmissivityTable& table, const std::string& key) {
    std::string out(kMagic);
    append(out, static_cast<std::uint32_t>(kEmissivityCacheVersion));
    out += key;
    append(out, static_cast<std::uint64_t>(table.wavelengths_um().size()));
    append(out, static_cast<std::uint64_t>(table.angles_rad().size()));
    for (const double w : table.wavelengths_um()) append(out, w);
    for (const StokesVector& v : table.values())
        for (int c = 0; c < 4; ++c) append(out, v[c]);
    append(out, fnv1a(out, kSecondBasis));
    return out;
}

/// The stored table if `bytes` is a complete, uncorrupted entry for `key` at `wavelengths_um`.
std::shared_ptr<const EmissivityTable> deserialize(std::string_view bytes, const std::string& key,
                                                   const std::vector<double>& wavelengths_um,
                                                   int angle_nodes) {
    if (bytes.size() < kMagic.size() + 8) return nullptr;
    std::uint64_t checksum = 0;
    std::memcpy(&checksum, bytes.data() + bytes.size() - 8, 8);
    std::string_view in = bytes.substr(0, bytes.size() - 8);
    if (fnv1a(in, kSecondBasis) != checksum) return nullptr;
    if (in.substr(0, kMagic.size()) != kMagic) return nullptr;
    in.remove_prefix(kMagic.size());
    std::uint32_t version = 0;
    if (!take(in, version) || version != kEmissivityCacheVersion) return nullptr;
    if (in.substr(0, key.size()) != key) return nullptr;
    in.remove_prefix(key.size());
    std::uint64_t n_wavelengths = 0, n_angles = 0;
    if (!take(in, n_wavelengths) || !take(in, n_angles)) return nullptr;
    if (n_wavelengths != wavelengths_um.size() ||
        n_angles != static_cast<std::uint64_t>(angle_nodes))
        return nullptr;
    if (in.size() != (n_wavelengths + n_wavelengths * n_angles * 4) * sizeof(double))
        return nullptr;
    std::vector<double> stored_wavelengths(n_wavelengths);
    for (double& w : stored_wavelengths) take(in, w);
    if (stored_wavelengths != wavelengths_um) return nullptr;
    std::vector<StokesVector> values(n_wavelengths * n_angles);
    for (StokesVector& v : values)
        for (int c = 0; c < 4; ++c) take(in, v[c]);
    try {
        return std::make_shared<const EmissivityTable>(EmissivityTable::from_values(
            std::move(stored_wavelengths), angle_nodes, std::move(values)));
    } catch (const Error&) {
        return nullptr;  // e.g. a non-finite value
    }
}

struct MemoryCache {
    std::mutex mutex;
    std::map<std::string, std::shared_ptr<const EmissivityTable>> tables;
};

MemoryCache& memory_cache() {
    static MemoryCache cache;
    return cache;
}

}  // namespace

std::filesystem::path default_emissivity_cache_directory() {
    if (const char* dir = std::getenv("TIRPOL_CACHE_DIR"); dir && *dir)
        return std::filesystem::path(dir);
    if (const char* xdg = std::getenv("XDG_CACHE_HOME");
        xdg && *xdg && std::filesystem::path(xdg).is_absolute())
        return std::filesystem::path(xdg) / "tirpol";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::filesystem::path(home) / ".cache" / "tirpol";
    return {};
}

std::string emissivity_table_key(const PolarizedBrdf& brdf,
                                 const std::vector<double>& wavelengths_um, int angle_nodes,
                                 const EmissivityOptions& options) {
    const std::string text = key_text(brdf, wavelengths_um, angle_nodes, options);
    return fmt::format("{:016x}{:016x}", fnv1a(text), fnv1a(text, kSecondBasis));
}

CachedEmissivityTable cached_emissivity_table(const PolarizedBrdf& brdf,
                                              const std::vector<double>& wavelengths_um,
                                              const std::filesystem::path& directory,
                                              int angle_nodes, const EmissivityOptions& options) {
    const std::string key = emissivity_table_key(brdf, wavelengths_um, angle_nodes, options);
    MemoryCache& memory = memory_cache();
    {
        const std::lock_guard lock(memory.mutex);
        if (auto it = memory.tables.find(key); it != memory.tables.end())
            return {it->second, EmissivityCacheSource::memory};
    }
    CachedEmissivityTable result;
    std::filesystem::path file;
    bool file_present = false;
    if (!directory.empty()) {
        file = directory / fmt::format("{}-{}.emtab", brdf.model(), key);
        std::error_code ec;
        file_present = std::filesystem::is_regular_file(file, ec);
        if (file_present) {
            try {
                result.table = deserialize(read_file(file), key, wavelengths_um, angle_nodes);
            } catch (const Error&) {
                result.table = nullptr;  // unreadable: rebuilt below
            }
            if (result.table) result.source = EmissivityCacheSource::disk;
        }
    }
    if (!result.table) {
        result.table =
            std::make_shared<const EmissivityTable>(brdf, wavelengths_um, angle_nodes, options);
        result.source =
            file_present ? EmissivityCacheSource::rebuilt_corrupt : EmissivityCacheSource::built;
        if (file_present)
            spdlog::warn("emissivity cache: {} was invalid; rebuilt it", file.string());
        if (!file.empty()) {
            try {
                std::filesystem::create_directories(directory);
                write_file_atomic(file, serialize(*result.table, key));
            } catch (const std::exception& e) {
                spdlog::warn(
                    "emissivity cache: cannot store {} ({}); tables will be rebuilt next time",
                    file.string(), e.what());
            }
        }
    }
    const std::lock_guard lock(memory.mutex);
    const auto [it, inserted] = memory.tables.emplace(key, result.table);
    return {it->second, result.source};
}

void clear_emissivity_memory_cache() {
    MemoryCache& memory = memory_cache();
    const std::lock_guard lock(memory.mutex);
    memory.tables.clear();
}

}  // namespace tirpol::materials
