// What `tirpol sweep` prints (sweep::sweep_summary_text): the counts, only the files written
// directly in the output folder, and each failed point with its error.

#include <gtest/gtest.h>

#include <algorithm>

#include "tirpol/sweep/sweep_run.h"

namespace tirpol::sweep {
namespace {

TEST(SweepSummaryText, CountsTopLevelOutputsAndFailedPointsWithTheirErrors) {
    SweepSummary s;
    s.ranks = 2;
    s.threads = 3;
    s.wall_seconds = 12.34;
    s.rendered = 1;
    s.resumed = 1;
    s.failed = 1;
    for (const char* id : {"p000", "p001", "p002"}) {
        PointRecord r;
        r.point.id = id;
        s.points.push_back(r);
    }
    s.points[0].status = "rendered";
    s.points[1].status = "resumed";
    s.points[2].status = "failed";
    s.points[2].error = "scene.yaml: no camera";
    const std::filesystem::path out = "/tmp/sweep-out";
    s.outputs = {out / "manifest.json", out / "plots" / "s0.svg", out / "results.csv"};
    const std::string text = sweep_summary_text(s, "day.yaml", out);
    EXPECT_NE(text.find("sweep day.yaml: 3 points on 2 rank(s) × 3 thread(s) in 12.3 s: 1 "
                        "rendered, 1 resumed, 1 failed\n"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("  /tmp/sweep-out/manifest.json\n"), std::string::npos) << text;
    EXPECT_NE(text.find("  /tmp/sweep-out/results.csv\n"), std::string::npos) << text;
    EXPECT_EQ(text.find("s0.svg"), std::string::npos) << "a file inside a subfolder was listed";
    EXPECT_NE(text.find("  FAILED p002: scene.yaml: no camera\n"), std::string::npos) << text;
    EXPECT_EQ(text.find("FAILED p000"), std::string::npos);
    EXPECT_EQ(text.find("FAILED p001"), std::string::npos);
}

TEST(SweepSummaryText, OutputPatternsCoverWhatASweepWrites) {
    const auto& patterns = sweep_output_patterns();
    for (const char* name : {"manifest.json", "results.csv", "results.json", "points", "plots"})
        EXPECT_NE(std::find(patterns.begin(), patterns.end(), name), patterns.end()) << name;
}

}  // namespace
}  // namespace tirpol::sweep
