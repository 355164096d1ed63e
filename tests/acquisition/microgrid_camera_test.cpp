// Requires TIRPOL_WITH_ARAVIS (built only with that back end: cmake/TirpolBackends.cmake).
// A microgrid (division-of-focal-plane) polarization camera over GigE Vision: Aravis's fake camera
// with tests/data/genicam/polarized-fake-camera.xml offers LUCID's PolarizeMono8/12/12p/16 raw
// mosaic formats (PFNC vendor codes) besides Mono8/Mono16. The aravis:// camera must receive each
// pixel exactly, report the sensor's 2×2 analyzer layout for the polarized formats, and take a
// declared layout (microgrid=) for a plain Mono16 stream.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>

#include "fake_gv_camera_process.h"
#include "test_support.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/sim/fake_gige_server.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

constexpr std::array<double, 4> kSonyLayoutDeg{90.0, 45.0, 135.0, 0.0};

/// A value for every pixel that differs from its neighbours in every bit position a packing error
/// would swap (low nibble, high nibble, the byte boundary), within `bits`.
float pixel_value(int x, int y, std::uint64_t frame_id, int bits) {
    const unsigned full = (1u << static_cast<unsigned>(bits)) - 1u;
    return static_cast<float>((static_cast<unsigned>(x) * 0x2F3u +
                               static_cast<unsigned>(y) * 0x51u +
                               static_cast<unsigned>(frame_id % 7u) * 0x111u) &
                              full);
}

FakeGigECameraOptions polarized_options() {
    FakeGigECameraOptions o;
    o.genicam_xml = test::source_dir() / "tests/data/genicam/polarized-fake-camera.xml";
    return o;
}

struct FormatCase {
    const char* name;
    int bits;
};

class PolarizedFormat : public ::testing::TestWithParam<FormatCase> {};

TEST_P(PolarizedFormat, DeliversEveryPixelExactlyWithTheSensorLayout) {
    const FormatCase format = GetParam();
    test::LoopbackGigELock lock;
    FakeGigECameraServer server(polarized_options());
    std::atomic<bool> request_ok{true};
    server.set_fill([&](const FakeGigEFrameRequest& r, std::vector<float>& counts) {
        if (r.pixel_format != format.name || r.bits_per_pixel != format.bits) request_ok = false;
        for (int y = 0; y < r.height; ++y)
            for (int x = 0; x < r.width; ++x)
                counts[static_cast<std::size_t>(y * r.width + x)] =
                    pixel_value(x, y, r.frame_id, format.bits);
    });
    auto opened = open_camera(fmt::format("aravis://{}?pixel_format={}&width=64&height=48&fps=50",
                                          server.device_id(), format.name));
    ASSERT_TRUE(opened.ok()) << opened.error().message;
    Camera& camera = *opened.value();
    const CameraInfo info = camera.info();
    EXPECT_EQ(info.pixel_format, format.name);
    EXPECT_EQ(info.bits_per_pixel, format.bits);
    ASSERT_TRUE(info.microgrid_pattern_deg);
    EXPECT_EQ(*info.microgrid_pattern_deg, kSonyLayoutDeg);
    ASSERT_TRUE(camera.start().ok());
    for (int i = 0; i < 3; ++i) {
        auto frame = camera.grab(2s);
        ASSERT_TRUE(frame.ok()) << frame.error().message;
        const Frame& f = frame.value();
        ASSERT_EQ(f.width, 64);
        ASSERT_EQ(f.counts.size(), 64u * 48u);
        const std::uint64_t raw_id = (f.frame_id - 1) % 65535 + 1;
        int wrong = 0;
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 64; ++x)
                wrong += f.counts[static_cast<std::size_t>(y * 64 + x)] !=
                         pixel_value(x, y, raw_id, format.bits);
        EXPECT_EQ(wrong, 0) << format.name << " frame " << f.frame_id;
    }
    ASSERT_TRUE(camera.stop().ok());
    EXPECT_TRUE(request_ok);
}

INSTANTIATE_TEST_SUITE_P(LucidNames, PolarizedFormat,
                         ::testing::Values(FormatCase{"PolarizeMono8", 8},
                                           FormatCase{"PolarizeMono12", 12},
                                           FormatCase{"PolarizeMono12p", 12},
                                           FormatCase{"PolarizeMono16", 16}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(MicrogridCamera, PlainMono16TakesTheDeclaredPatternAndAPolarizedFormatMayOverrideIt) {
    test::LoopbackGigELock lock;
    FakeGigECameraServer server(polarized_options());
    {
        auto plain = open_camera(fmt::format("aravis://{}?pixel_format=Mono16&width=64&height=48",
                                             server.device_id()))
                         .value_or_throw();
        EXPECT_FALSE(plain->info().microgrid_pattern_deg) << "a plain camera has no microgrid";
    }
    {
        auto declared =
            open_camera(fmt::format("aravis://{}?pixel_format=Mono16&width=64&height=48&"
                                    "microgrid=0,45,135,90",
                                    server.device_id()))
                .value_or_throw();
        ASSERT_TRUE(declared->info().microgrid_pattern_deg);
        EXPECT_EQ(*declared->info().microgrid_pattern_deg,
                  (std::array<double, 4>{0.0, 45.0, 135.0, 90.0}));
    }
    auto mirrored =
        open_camera(fmt::format("aravis://{}?pixel_format=PolarizeMono8&width=64&height=48&"
                                "microgrid=45,90,0,135",
                                server.device_id()))
            .value_or_throw();
    ASSERT_TRUE(mirrored->info().microgrid_pattern_deg);
    EXPECT_EQ(*mirrored->info().microgrid_pattern_deg,
              (std::array<double, 4>{45.0, 90.0, 0.0, 135.0}));
}

TEST(MicrogridCamera, ABadDeclaredPatternIsRefusedNamingTheUriAndTheAngle) {
    const auto error_of = [](const std::string& query) {
        try {
            (void)open_camera("aravis://Aravis-Fake-NONE?" + query);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_THAT(error_of("microgrid=0,45,90"),
                HasSubstr("microgrid: '0,45,90': expected \"sony\" or four comma-separated"));
    EXPECT_THAT(error_of("microgrid=0,45,90,180"),
                HasSubstr("angle 4 is '180' (expected a number in [0, 180) degrees)"));
    EXPECT_THAT(error_of("microgrid=0,45,x,135"), HasSubstr("angle 3 is 'x'"));
    EXPECT_THAT(error_of("microgrid=0,45,45,135"), HasSubstr("angle 3 repeats angle 2"));
    EXPECT_EQ(parse_microgrid_pattern_deg("sony", "test"), kSonyLayoutDeg);
}

}  // namespace
}  // namespace tirpol::acquisition
