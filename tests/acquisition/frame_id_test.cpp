// The frame-id unwrapper on its own. Counter rules: GigE Vision 1.x GVSP block ids are 16-bit and 0
// is reserved, so the fake camera counts 65534, 65535, 1, 2 (Aravis 0.8.26 src/arvfakecamera.c,
// arv_fake_camera_fill_buffer: "frame id is a 16 bit value, 0 is invalid"); V4L2 sequence numbers
// are 32-bit and count through 0 (Linux media docs, struct v4l2_buffer "sequence").

#include "tirpol/acquisition/internal/frame_id.h"

#include <gtest/gtest.h>

namespace tirpol::acquisition {
namespace {

TEST(FrameIdUnwrapper, FirstIdIsKeptAsIs) {
    auto u = FrameIdUnwrapper::gige_vision_16bit();
    const FrameIdStep s = u.next(65400);
    EXPECT_EQ(s.id, 65400u);
    EXPECT_EQ(s.missed, 0u);
}

TEST(FrameIdUnwrapper, GigEVisionWrapSkipsZeroWithoutCountingALoss) {
    auto u = FrameIdUnwrapper::gige_vision_16bit();
    u.next(65534);
    EXPECT_EQ(u.next(65535).id, 65535u);
    const FrameIdStep s = u.next(1);  // 65535 → 1 is one step: 0 is never sent
    EXPECT_EQ(s.id, 65536u);
    EXPECT_EQ(s.missed, 0u);
    EXPECT_EQ(u.next(2).id, 65537u);
}

TEST(FrameIdUnwrapper, GapAcrossTheWrapCountsExactlyTheMissingFrames) {
    auto u = FrameIdUnwrapper::gige_vision_16bit();
    u.next(65533);
    // Missing: 65534, 65535, 1 → three frames lost.
    const FrameIdStep s = u.next(2);
    EXPECT_EQ(s.missed, 3u);
    EXPECT_EQ(s.id, 65533u + 4u);
}

TEST(FrameIdUnwrapper, IdsStayMonotonicOverManyWraps) {
    auto u = FrameIdUnwrapper::gige_vision_16bit();
    std::uint64_t raw = 65400, previous = 0, missed = 0;
    for (int i = 0; i < 300000; ++i) {
        const std::uint64_t step = (i % 7 == 0) ? 3 : 1;  // lose two frames every seventh
        raw = (raw - 1 + step) % 65535 + 1;
        const FrameIdStep s = u.next(raw);
        if (i > 0) {
            ASSERT_GT(s.id, previous);
            missed += s.missed;
        }
        previous = s.id;
    }
    // i = 0 is the first frame (no loss counted); each of the 299999 / 7 later multiples of 7 lost
    // two.
    EXPECT_EQ(missed, 2u * (299999u / 7u));
}

TEST(FrameIdUnwrapper, V4l2SequenceWrapsThroughZero) {
    auto u = FrameIdUnwrapper::v4l2_sequence();
    u.next(0xFFFFFFFEu);
    EXPECT_EQ(u.next(0xFFFFFFFFu).missed, 0u);
    const FrameIdStep s = u.next(0);
    EXPECT_EQ(s.missed, 0u);
    EXPECT_EQ(s.id, 0x100000000u);
    EXPECT_EQ(u.next(5).missed, 4u);
}

TEST(FrameIdUnwrapper, RepeatedIdIsADuplicateNotAFrame) {
    auto u = FrameIdUnwrapper::gige_vision_16bit();
    u.next(10);
    const FrameIdStep s = u.next(10);
    EXPECT_TRUE(s.duplicate);
    EXPECT_EQ(s.id, 10u);
    EXPECT_EQ(u.next(11).id, 11u);
}

TEST(FrameIdUnwrapper, BackwardJumpIsACounterResetNotAHugeLoss) {
    auto u = FrameIdUnwrapper::gige_vision_16bit();
    u.next(40000);
    const FrameIdStep s = u.next(5);
    // 40000 → 5 forward is 65535 − 40000 + 5 = 25540 steps (less than half): read as a loss.
    EXPECT_FALSE(s.reset);
    EXPECT_EQ(s.missed, 25539u);
    const FrameIdStep back = u.next(3);  // 5 → 3 forward would be 65533 steps: a reset
    EXPECT_TRUE(back.reset);
    EXPECT_EQ(back.missed, 0u);
    EXPECT_EQ(back.id, s.id + 1);
}

}  // namespace
}  // namespace tirpol::acquisition
