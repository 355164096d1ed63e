// The emissivity-table cache (emissivity_cache.h): a table read back from memory or disk equals the
// one built from the model; a changed material, band grid or corrupt file never returns stale
// numbers.

#include <gtest/gtest.h>

#include <fstream>

#include "test_support.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::materials {
namespace {

using tirpol::test::TempDir;

MicrofacetBrdf rough(double n, double sigma) {
    MicrofacetParameters p;
    p.index = RefractiveIndexTable::constant({n, 0.1});
    p.sigma = sigma;
    p.rho_d = 0.01;
    return MicrofacetBrdf(p);
}

const std::vector<double> kGrid = {8.0, 9.0, 10.5};
constexpr int kAngles = 9;  // small tables keep the test fast; the key includes the angle count
const EmissivityOptions kQuick{4, 4, 4};

void expect_same_values(const EmissivityTable& a, const EmissivityTable& b) {
    ASSERT_EQ(a.wavelengths_um(), b.wavelengths_um());
    ASSERT_EQ(a.values().size(), b.values().size());
    for (std::size_t i = 0; i < a.values().size(); ++i)
        EXPECT_EQ(a.values()[i], b.values()[i]) << i;
}

std::vector<std::filesystem::path> files_in(const std::filesystem::path& dir) {
    std::vector<std::filesystem::path> out;
    for (const auto& e : std::filesystem::directory_iterator(dir)) out.push_back(e.path());
    return out;
}

TEST(EmissivityCache, MemoryThenDiskThenMemoryGiveTheBuiltTable) {
    TempDir dir;
    clear_emissivity_memory_cache();
    const MicrofacetBrdf brdf = rough(1.6, 0.3);
    const EmissivityTable direct(brdf, kGrid, kAngles, kQuick);

    const auto first = cached_emissivity_table(brdf, kGrid, dir.path(), kAngles, kQuick);
    EXPECT_EQ(first.source, EmissivityCacheSource::built);
    expect_same_values(*first.table, direct);
    ASSERT_EQ(files_in(dir.path()).size(), 1u);
    EXPECT_EQ(files_in(dir.path())[0].extension(), ".emtab");

    const auto again = cached_emissivity_table(brdf, kGrid, dir.path(), kAngles, kQuick);
    EXPECT_EQ(again.source, EmissivityCacheSource::memory);
    EXPECT_EQ(again.table.get(), first.table.get());

    clear_emissivity_memory_cache();  // as a new process would start
    const auto loaded = cached_emissivity_table(brdf, kGrid, dir.path(), kAngles, kQuick);
    EXPECT_EQ(loaded.source, EmissivityCacheSource::disk);
    expect_same_values(*loaded.table, direct);
}

// A material edited between runs (another index or roughness) has another key: its table is built
// anew from the new parameters, never read from the old file. Likewise another spectral grid.
TEST(EmissivityCache, ChangedMaterialOrGridInvalidatesTheEntry) {
    TempDir dir;
    clear_emissivity_memory_cache();
    const MicrofacetBrdf original = rough(1.6, 0.3);
    cached_emissivity_table(original, kGrid, dir.path(), kAngles, kQuick);
    clear_emissivity_memory_cache();

    for (const MicrofacetBrdf& edited : {rough(1.7, 0.3), rough(1.6, 0.31)}) {
        EXPECT_NE(emissivity_table_key(edited, kGrid, kAngles, kQuick),
                  emissivity_table_key(original, kGrid, kAngles, kQuick));
        const auto c = cached_emissivity_table(edited, kGrid, dir.path(), kAngles, kQuick);
        EXPECT_EQ(c.source, EmissivityCacheSource::built);
        expect_same_values(*c.table, EmissivityTable(edited, kGrid, kAngles, kQuick));
    }
    const std::vector<double> other_grid = {8.0, 9.0, 10.25};
    EXPECT_EQ(cached_emissivity_table(original, other_grid, dir.path(), kAngles, kQuick).source,
              EmissivityCacheSource::built);
    EXPECT_EQ(cached_emissivity_table(original, kGrid, dir.path(), kAngles + 2, kQuick).source,
              EmissivityCacheSource::built);
    EXPECT_EQ(files_in(dir.path()).size(), 5u);
}

// A damaged file (truncated, a flipped byte) is detected by its checksum/size, rebuilt and
// replaced.
TEST(EmissivityCache, CorruptFileIsRebuiltNeverTrusted) {
    TempDir dir;
    const MicrofacetBrdf brdf = rough(1.55, 0.2);
    const EmissivityTable direct(brdf, kGrid, kAngles, kQuick);
    clear_emissivity_memory_cache();
    cached_emissivity_table(brdf, kGrid, dir.path(), kAngles, kQuick);
    const auto file = files_in(dir.path()).at(0);
    const auto size = std::filesystem::file_size(file);

    for (int damage = 0; damage < 3; ++damage) {
        clear_emissivity_memory_cache();
        if (damage == 0) {
            std::filesystem::resize_file(file, size / 2);
        } else {
            const auto at =
                static_cast<std::streamoff>(damage == 1 ? size - 100 : 20);  // a value, the key
            std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
            f.seekg(at);
            const char byte = static_cast<char>(f.get());
            f.seekp(at);
            f.put(static_cast<char>(~byte));
        }
        const auto c = cached_emissivity_table(brdf, kGrid, dir.path(), kAngles, kQuick);
        EXPECT_EQ(c.source, EmissivityCacheSource::rebuilt_corrupt) << damage;
        expect_same_values(*c.table, direct);
        clear_emissivity_memory_cache();
        EXPECT_EQ(cached_emissivity_table(brdf, kGrid, dir.path(), kAngles, kQuick).source,
                  EmissivityCacheSource::disk)
            << "the rebuilt file replaced the damaged one";
    }
}

// An unwritable cache folder costs the rebuild, not the result.
TEST(EmissivityCache, UnusableFolderStillGivesTheTable) {
    TempDir dir;
    tirpol::test::write_text(dir / "not_a_folder", "x");
    clear_emissivity_memory_cache();
    const MicrofacetBrdf brdf = rough(1.5, 0.25);
    const auto c = cached_emissivity_table(brdf, kGrid, dir / "not_a_folder", kAngles, kQuick);
    EXPECT_EQ(c.source, EmissivityCacheSource::built);
    expect_same_values(*c.table, EmissivityTable(brdf, kGrid, kAngles, kQuick));
}

TEST(EmissivityCache, DefaultFolderFollowsTheEnvironment) {
    const char* saved_dir = std::getenv("TIRPOL_CACHE_DIR");
    const char* saved_xdg = std::getenv("XDG_CACHE_HOME");
    const std::string keep_dir = saved_dir ? saved_dir : "", keep_xdg = saved_xdg ? saved_xdg : "";
    setenv("TIRPOL_CACHE_DIR", "/tmp/tirpol-cache-override", 1);
    EXPECT_EQ(default_emissivity_cache_directory(),
              std::filesystem::path("/tmp/tirpol-cache-override"));
    unsetenv("TIRPOL_CACHE_DIR");
    setenv("XDG_CACHE_HOME", "/tmp/xdg", 1);
    EXPECT_EQ(default_emissivity_cache_directory(), std::filesystem::path("/tmp/xdg/tirpol"));
    setenv("XDG_CACHE_HOME", "relative/ignored", 1);  // XDG: relative paths are invalid
    EXPECT_EQ(default_emissivity_cache_directory().filename(), "tirpol");
    EXPECT_NE(default_emissivity_cache_directory(),
              std::filesystem::path("relative/ignored/tirpol"));
    if (saved_dir) setenv("TIRPOL_CACHE_DIR", keep_dir.c_str(), 1);
    if (saved_xdg)
        setenv("XDG_CACHE_HOME", keep_xdg.c_str(), 1);
    else
        unsetenv("XDG_CACHE_HOME");
}

}  // namespace
}  // namespace tirpol::materials
