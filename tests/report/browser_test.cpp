// The report in a real browser (Debian's chromium, headless): the page loads offline with no
// console error, every <img> is an embedded data: URI, the expected sections are there, and a
// screenshot shows the images (non-blank, with colour). Skipped only when /usr/bin/chromium is
// absent. Set TIRPOL_REPORT_TEST_OUTPUT=DIR to keep the report and the screenshot for a look.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "synthetic_pair.h"
#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/config.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/report/comparison_report.h"

using namespace tirpol::report;
using ::testing::HasSubstr;

namespace {

constexpr const char* kChromium = "/usr/bin/chromium";

// Runs chromium headless on `url` with `extra` arguments, stdout/stderr to files, killed after 90
// s.
int run_chromium(const std::filesystem::path& profile, const std::string& extra,
                 const std::string& url, const std::filesystem::path& out,
                 const std::filesystem::path& err) {
    const std::string command =
        std::string("timeout -k 5 90 ") + kChromium +
        " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run"
        " --disable-background-networking --disable-component-update --disable-sync"
        " --user-data-dir=" +
        profile.string() + " " + extra + " '" + url + "' > '" + out.string() + "' 2> '" +
        err.string() + "'";
    return std::system(command.c_str());
}

}  // namespace

TEST(ReportBrowser, HeadlessChromiumLoadsTheReportWithoutErrorsAndShowsTheImages) {
    if (!std::filesystem::exists(kChromium))
        FAIL() << kChromium << " is absent: install the Debian package chromium (./run does)";
    tirpol::test::TempDir temp("tirpol-report-browser");
    const char* keep = std::getenv("TIRPOL_REPORT_TEST_OUTPUT");
    const std::filesystem::path dir = keep ? std::filesystem::path(keep) : temp.path();
    std::filesystem::create_directories(dir);

    test::SyntheticPairOptions o;
    o.width = 240;
    o.height = 180;
    o.shift_x_px = 1.6;
    o.shift_y_px = -0.8;
    o.s1_bias = 0.1;
    const auto pair = test::make_synthetic_pair(o);
    tirpol::write_exr(dir / "measured.exr", pair.measured);
    tirpol::write_exr(dir / "simulated.exr", pair.simulated);
    tirpol::write_file_atomic(dir / "rois.yaml", pair.regions_yaml);
    CompareOptions options;
    options.measured_name = "measured.exr";
    options.simulated_name = "simulated.exr";
    options.regions = load_regions(dir / "rois.yaml");
    // A name OpenCV's Hershey fonts cannot draw: the overview names regions in SVG text.
    const std::string unicode_name = "Schnee ❄ Süd";
    options.regions->regions.push_back(
        {unicode_name, {{20, 20}, {60, 20}, {60, 50}, {20, 50}}, ""});
    const auto result =
        write_comparison_report(pair.measured, pair.simulated, options, dir / "report");
    const std::string url = "file://" + std::filesystem::absolute(result.html).string();

    // One headless run: DOM to stdout, console log to stderr, screenshot to a file.
    const auto shot = dir / "screenshot.png";
    ASSERT_EQ(
        run_chromium(temp / "profile",
                     "--enable-logging=stderr --v=0 --hide-scrollbars --window-size=1280,2000 "
                     "--screenshot=" +
                         shot.string() + " --dump-dom",
                     url, dir / "dom.html", dir / "chromium.log"),
        0)
        << tirpol::read_file(dir / "chromium.log");

    // DOM and console: every section rendered, every image embedded, no console error.
    const std::string dom = tirpol::read_file(dir / "dom.html");
    const std::string log = tirpol::read_file(dir / "chromium.log");
    for (const char* heading :
         {"Measured vs simulated Stokes images", "Summary", "Registration", "Regions of interest",
          "Stokes images side by side", "Region statistics", "Do the differences exceed the noise?",
          "Scatter plots", "Histograms of the differences", "Provenance", "Angle of polarization"})
        EXPECT_THAT(dom, HasSubstr(std::string(">") + heading + "<")) << heading;
    std::size_t images = 0;
    for (std::size_t at = dom.find("<img "); at != std::string::npos;
         at = dom.find("<img ", at + 1)) {
        ++images;
        const std::size_t src = dom.find("src=\"", at);
        ASSERT_NE(src, std::string::npos);
        EXPECT_EQ(dom.compare(src + 5, 22, "data:image/png;base64,"), 0) << dom.substr(src, 40);
    }
    std::size_t figures = 0;  // the PNGs shown: all but the parts of the composed panels
    for (const auto& png : result.pngs) {
        const std::string name = png.filename().string();
        if (name.rfind("measured_", 0) && name.rfind("simulated_", 0) &&
            name.rfind("difference_", 0) && name.rfind("z_", 0))
            ++figures;
    }
    EXPECT_EQ(images, figures);
    EXPECT_GE(images, 6u);  // the five panels and the z panel
    std::size_t svgs = 0;   // plots, inline
    for (std::size_t at = dom.find("<svg "); at != std::string::npos;
         at = dom.find("<svg ", at + 1))
        ++svgs;
    EXPECT_EQ(svgs, result.svgs.size());
    EXPECT_GE(svgs, 10u);  // the plots and the region overview
    EXPECT_THAT(dom, HasSubstr(">" + unicode_name + "</text>"))
        << "the region name is not SVG text in the page";
    EXPECT_THAT(log, ::testing::Not(HasSubstr("Uncaught")));
    EXPECT_THAT(log, ::testing::Not(HasSubstr("ERROR:CONSOLE")));
    EXPECT_THAT(log, ::testing::Not(HasSubstr("Failed to load resource")));

    // Screenshot: right size, not blank, and colourful where the figures are.
    const cv::Mat png = cv::imread(shot.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(png.empty()) << "no screenshot at " << shot;
    EXPECT_EQ(png.cols, 1280);
    EXPECT_EQ(png.rows, 2000);
    cv::Scalar mean, stddev;
    cv::meanStdDev(png, mean, stddev);
    EXPECT_GT(stddev[0] + stddev[1] + stddev[2], 30.0) << "blank screenshot";
    cv::Mat hsv;
    cv::cvtColor(png, hsv, cv::COLOR_BGR2HSV);
    cv::Mat saturated;
    cv::inRange(hsv, cv::Scalar(0, 80, 40), cv::Scalar(180, 255, 255), saturated);
    EXPECT_GT(cv::countNonZero(saturated), png.total() / 50) << "the colour figures do not show";
}

// Region names in the real page: the boxes the browser gives the overview's labels
// (getBoundingClientRect, read by a script added to a copy of the page: the report itself has no
// script) never intersect and never leave the picture, for nine crowded panels with long names and
// one at the picture's right edge (where "flat_black_paint" used to be cut to "flat_black_pai").
TEST(ReportBrowser, RegionLabelsNeitherOverlapNorLeaveThePicture) {
    if (!std::filesystem::exists(kChromium))
        FAIL() << kChromium << " is absent: install the Debian package chromium (./run does)";
    tirpol::test::TempDir temp("tirpol-report-labels");
    const char* keep = std::getenv("TIRPOL_REPORT_TEST_OUTPUT");
    const std::filesystem::path dir = keep ? std::filesystem::path(keep) / "labels" : temp.path();
    std::filesystem::create_directories(dir);

    test::SyntheticPairOptions o;
    o.width = 240;
    o.height = 180;
    const auto pair = test::make_synthetic_pair(o);
    CompareOptions options;
    options.registration = RegistrationMethod::None;
    RegionSet regions;
    const std::vector<std::string> names = {
        "glossy_black_paint",      "rough_aluminium",     "white_paint_panel",
        "specular_gold_reflector", "oxidised_copper",     "painted_steel_blue",
        "anodised_aluminium",      "rough_concrete_slab", "Schnee ❄ Süd"};
    for (std::size_t i = 0; i < names.size(); ++i) {
        const double x = 90.0 + 22.0 * static_cast<double>(i % 3);
        const double y = 60.0 + 22.0 * static_cast<double>(i / 3);
        regions.regions.push_back(
            {names[i], {{x, y}, {x + 18, y}, {x + 18, y + 18}, {x, y + 18}}, ""});
    }
    regions.regions.push_back(
        {"flat_black_paint", {{222, 10}, {238, 10}, {238, 30}, {222, 30}}, ""});
    options.regions = regions;
    const auto result =
        write_comparison_report(pair.measured, pair.simulated, options, dir / "report");
    std::string page = tirpol::read_file(result.html);
    EXPECT_EQ(page.find("<script"), std::string::npos) << "the report page has no script";
    const std::string probe = R"(<script>
(function () {
  const svg = document.querySelector('svg.region-overview');
  const box = (e) => { const r = e.getBoundingClientRect(); return [r.left, r.top, r.right, r.bottom]; };
  const out = {image: box(svg.querySelector('image')), labels: []};
  for (const t of svg.querySelectorAll('text.region-label'))
    out.labels.push({name: t.textContent, box: box(t)});
  const pre = document.createElement('pre');
  pre.id = 'label-boxes';
  pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
})();
</script>
)";
    const std::size_t body_end = page.rfind("</body>");
    ASSERT_NE(body_end, std::string::npos);
    page.insert(body_end, probe);
    tirpol::write_file_atomic(dir / "probe.html", page);
    ASSERT_EQ(run_chromium(temp / "profile", "--window-size=1280,2000 --dump-dom",
                           "file://" + std::filesystem::absolute(dir / "probe.html").string(),
                           dir / "dom.html", dir / "chromium.log"),
              0)
        << tirpol::read_file(dir / "chromium.log");
    const std::string dom = tirpol::read_file(dir / "dom.html");
    const std::size_t open = dom.find("<pre id=\"label-boxes\">");
    ASSERT_NE(open, std::string::npos) << "the probe script did not run";
    const std::size_t start = dom.find('>', open) + 1;
    const auto boxes = nlohmann::json::parse(dom.substr(start, dom.find("</pre>", start) - start));

    const auto image = boxes.at("image").get<std::array<double, 4>>();
    const auto& labels = boxes.at("labels");
    ASSERT_EQ(labels.size(), names.size() + 1);
    std::vector<std::array<double, 4>> b;
    for (const auto& label : labels) {
        const auto r = label.at("box").get<std::array<double, 4>>();
        const std::string name = label.at("name").get<std::string>();
        EXPECT_GT(r[2] - r[0], 10.0) << name << ": no width";
        EXPECT_GE(r[0], image[0]) << name << " leaves the picture on the left";
        EXPECT_GE(r[1], image[1]) << name << " leaves the picture at the top";
        EXPECT_LE(r[2], image[2]) << name << " leaves the picture on the right";
        EXPECT_LE(r[3], image[3]) << name << " leaves the picture at the bottom";
        b.push_back(r);
    }
    for (std::size_t i = 0; i < b.size(); ++i)
        for (std::size_t j = i + 1; j < b.size(); ++j) {
            const bool intersect =
                b[i][0] < b[j][2] && b[j][0] < b[i][2] && b[i][1] < b[j][3] && b[j][1] < b[i][3];
            EXPECT_FALSE(intersect) << labels[i].at("name") << " and " << labels[j].at("name");
        }
}
