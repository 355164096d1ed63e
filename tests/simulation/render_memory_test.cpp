// Render memory does not grow with the samples per pixel: every random number is computed from
// (seed, pixel, replicate, sample, dimension) and pixels accumulate replicate means as they go, so
// a 1-pixel render at 2^19 spp allocates what one at 16 spp does. (Per-pixel stratum tables of spp
// integers per dimension once made a 4×4 render at 2e9 spp reach 10 GB.) The count is of every byte
// requested from operator new during the render, freed or not, so a per-sample allocation fails
// too.

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "scene_fixtures.h"

namespace {
std::atomic<bool> g_counting{false};
std::atomic<std::size_t> g_bytes{0};
}  // namespace

void* operator new(std::size_t size) {
    if (g_counting.load(std::memory_order_relaxed))
        g_bytes.fetch_add(size, std::memory_order_relaxed);
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace tirpol::simulation {
namespace {

std::size_t bytes_allocated_by_render(const Scene& scene) {
    RenderOptions options;
    options.threads = 1;
    g_bytes = 0;
    g_counting = true;
    const Image image = render(scene, options);
    g_counting = false;
    EXPECT_TRUE(std::isfinite(image.channel("S0")[0]));
    return g_bytes.load();
}

TEST(RenderMemory, AllocationsDoNotGrowWithSamplesPerPixel) {
    tirpol::test::TempDir dir;
    const auto scene_with = [&](int spp) {
        // One pixel looking at a uniform sky over a ground plane: one cheap ray per sample.
        return test::load_scene_text(
            dir,
            test::scene_header(1, 1, spp, 4,
                               "fov_deg: 10, position: [0, 0, 1], look_at: [0, 10, 3]",
                               "{type: uniform, temperature: 250}") +
                "objects:\n  - {name: ground, geometry: {type: plane, size: [10, 10]}, material: " +
                test::kGreyDiffuse + ", temperature: 280}\n");
    };
    (void)bytes_allocated_by_render(scene_with(16));  // fills the emissivity-table cache in memory
    const std::size_t small = bytes_allocated_by_render(scene_with(16));
    const std::size_t large = bytes_allocated_by_render(scene_with(1 << 19));
    std::printf("bytes allocated by a 1-pixel render: %zu at 16 spp, %zu at 2^19 spp\n", small,
                large);
    // 2^19 spp of one int per sample and dimension would be 2 MiB per dimension.
    EXPECT_LT(large, small + 64 * 1024);
}

}  // namespace
}  // namespace tirpol::simulation
