// Contact sheets and the time-of-day animation (sweep_results.h).

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "records_json.h"
#include "results.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/quicklook.h"

namespace tirpol::sweep::detail {

namespace {

constexpr const char* kSheetChannels[] = {"S0", "S1"};

std::string point_label(const SweepSpec& spec, const SweepPoint& p) {
    std::string label = p.id;
    for (std::size_t a = 0; a < spec.axes.size(); ++a)
        label += " " + spec.axes[a].labels[p.value_index[a]];
    return label;
}

void write_png(const std::filesystem::path& path, const cv::Mat& image) {
    AtomicFile file(path);
    if (!cv::imwrite(file.temp_path().string(), image))
        fail("{}: writing PNG failed", path.string());
    file.commit();
}

/// Pads `image` with white to `rows` × `cols`.
cv::Mat padded(const cv::Mat& image, int rows, int cols) {
    cv::Mat out;
    cv::copyMakeBorder(image, out, 0, rows - image.rows, 0, cols - image.cols, cv::BORDER_CONSTANT,
                       cv::Scalar(255, 255, 255));
    return out;
}

/// One quicklook per point and channel on a colour range common to all points (so that the sheet
/// compares points), in tiles/<id>_<channel>.png; tiles[channel][point] (empty Mat for a failed
/// point).
std::vector<std::vector<cv::Mat>> write_tiles(const SweepSpec& spec,
                                              const std::filesystem::path& out_dir,
                                              const std::vector<PointRecord>& points,
                                              std::vector<std::filesystem::path>& written) {
    const auto exr = [&](std::size_t i) {
        return out_dir / "points" / points[i].point.id / "stokes.exr";
    };
    // The common range from a sample of every point's pixels (at most kRangeSamples per point), so
    // memory does not grow with the sweep; each image is read again for its tile.
    constexpr std::size_t kRangeSamples = 20000;
    std::vector<std::vector<float>> samples(std::size(kSheetChannels));
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!points[i].statistics) continue;
        const Image image = read_exr(exr(i));
        const std::size_t stride = std::max<std::size_t>(1, image.pixel_count() / kRangeSamples);
        for (std::size_t c = 0; c < samples.size(); ++c)
            for (std::size_t k = 0; k < image.pixel_count(); k += stride)
                samples[c].push_back(image.channel(kSheetChannels[c])[k]);
    }
    std::vector<std::vector<cv::Mat>> tiles(samples.size(), std::vector<cv::Mat>(points.size()));
    std::filesystem::create_directories(out_dir / "tiles");
    std::vector<QuicklookOptions> options(samples.size());
    for (std::size_t c = 0; c < samples.size(); ++c) {
        options[c].colormap = default_colormap(kSheetChannels[c]);
        options[c].units = "W/(m²·sr)";
        std::tie(options[c].vmin, options[c].vmax) = quicklook_range(samples[c], options[c]);
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!points[i].statistics) continue;
        const Image image = read_exr(exr(i));
        for (std::size_t c = 0; c < samples.size(); ++c) {
            options[c].title =
                fmt::format("{} {}", kSheetChannels[c], point_label(spec, points[i].point));
            const auto path =
                out_dir / "tiles" / fmt::format("{}_{}.png", points[i].point.id, kSheetChannels[c]);
            write_quicklook(path, image.channel(kSheetChannels[c]), image.width(), image.height(),
                            options[c]);
            written.push_back(path);
            tiles[c][i] = cv::imread(path.string(), cv::IMREAD_COLOR);
            if (tiles[c][i].empty()) fail("{}: could not read back the tile", path.string());
        }
    }
    return tiles;
}

cv::Mat contact_sheet(const std::vector<cv::Mat>& tiles) {
    int rows = 1, cols = 1, n = 0;
    for (const auto& t : tiles) {
        if (t.empty()) continue;
        rows = std::max(rows, t.rows);
        cols = std::max(cols, t.cols);
        ++n;
    }
    const int per_row = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)))));
    const int sheet_rows = (n + per_row - 1) / per_row;
    cv::Mat sheet(std::max(1, sheet_rows) * rows, per_row * cols, CV_8UC3,
                  cv::Scalar(255, 255, 255));
    int k = 0;
    for (const auto& t : tiles) {
        if (t.empty()) continue;
        t.copyTo(sheet(cv::Rect((k % per_row) * cols, (k / per_row) * rows, t.cols, t.rows)));
        ++k;
    }
    return sheet;
}

std::string html_page(const nlohmann::json& frames) {
    std::string data = frames.dump();
    // Inside <script>, "</script>" in a label would end the script: JSON allows "<" as \u003c.
    for (std::size_t at = data.find('<'); at != std::string::npos; at = data.find('<', at))
        data.replace(at, 1, "\\u003c");
    return fmt::format(R"(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>tirpol sweep: time of day</title>
<style>body{{font-family:sans-serif;margin:1em}} img{{max-width:100%}}</style></head>
<body><h1>Time of day ({} frames)</h1>
<p>S0 and S1 of each time, on the colour ranges of the contact sheets; other axes at their first value.</p>
<img id="frame" alt="frame"><br>
<button id="play">pause</button> <input type="range" id="slider" min="0" value="0"> <span id="label"></span>
<script>
const frames = {};
const img = document.getElementById("frame"), slider = document.getElementById("slider"),
      label = document.getElementById("label"), play = document.getElementById("play");
let current = 0, playing = true;
slider.max = frames.length - 1;
function show(k) {{ current = k; img.src = frames[k].src; slider.value = k; label.textContent = frames[k].label; }}
play.onclick = () => {{ playing = !playing; play.textContent = playing ? "pause" : "play"; }};
slider.oninput = () => show(Number(slider.value));
setInterval(() => {{ if (playing) show((current + 1) % frames.length); }}, 600);
show(0);
</script></body></html>
)",
                       frames.size(), data);
}

}  // namespace

std::vector<std::filesystem::path> write_image_summaries(const SweepSpec& spec,
                                                         const std::filesystem::path& out_dir,
                                                         const std::vector<PointRecord>& points) {
    std::vector<std::filesystem::path> written;
    const auto tiles = write_tiles(spec, out_dir, points, written);
    if (written.empty()) return written;
    for (std::size_t c = 0; c < tiles.size(); ++c) {
        written.push_back(out_dir / fmt::format("contact_sheet_{}.png", kSheetChannels[c]));
        write_png(written.back(), contact_sheet(tiles[c]));
    }
    const auto time_axis = std::find_if(spec.axes.begin(), spec.axes.end(),
                                        [](const Axis& a) { return a.parameter == "time"; });
    if (time_axis == spec.axes.end()) return written;
    const auto t = static_cast<std::size_t>(time_axis - spec.axes.begin());
    auto line = points_along(spec, points, t);
    std::stable_sort(line.begin(), line.end(), [&](std::size_t a, std::size_t b) {
        return time_axis->coordinates[points[a].point.value_index[t]] <
               time_axis->coordinates[points[b].point.value_index[t]];
    });
    std::filesystem::create_directories(out_dir / "animation");
    nlohmann::json frames = nlohmann::json::array();
    for (std::size_t i : line) {
        if (tiles[0][i].empty()) continue;
        const int rows = std::max(tiles[0][i].rows, tiles[1][i].rows);
        cv::Mat frame;
        cv::hconcat(padded(tiles[0][i], rows, tiles[0][i].cols),
                    padded(tiles[1][i], rows, tiles[1][i].cols), frame);
        const std::string name = fmt::format("frame_{:03}.png", frames.size());
        write_png(out_dir / "animation" / name, frame);
        written.push_back(out_dir / "animation" / name);
        frames.push_back(
            {{"src", name}, {"label", time_axis->labels[points[i].point.value_index[t]]}});
    }
    if (frames.empty()) return written;
    written.push_back(out_dir / "animation" / "index.html");
    write_file_atomic(written.back(), html_page(frames));
    return written;
}

}  // namespace tirpol::sweep::detail
