#include "tirpol/report/regions.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <set>

#include "tirpol/core/config.h"
#include "tirpol/core/error.h"

namespace tirpol::report {

namespace {

PixelPoint parse_point(const ConfigNode& node) {
    const auto xy = node.as<std::vector<double>>();
    if (xy.size() != 2)
        node.fail(fmt::format("expected a point [x, y] in pixels, got {} numbers", xy.size()));
    if (!std::isfinite(xy[0]) || !std::isfinite(xy[1]))
        node.fail("expected finite pixel coordinates");
    return {xy[0], xy[1]};
}

}  // namespace

std::string regions_yaml(const RegionSet& set) {
    // JSON strings are valid YAML double-quoted scalars for the characters a name holds.
    auto quoted = [](const std::string& text) {
        std::string out = "\"";
        for (char c : text) {
            if (c == '"' || c == '\\') out += '\\';
            out += c;
        }
        return out + "\"";
    };
    std::string y = "regions:\n";
    for (const auto& region : set.regions) {
        y += "  - name: " + quoted(region.name) + "\n    polygon: [";
        for (std::size_t i = 0; i < region.polygon.size(); ++i)
            y += fmt::format("{}[{:.17g}, {:.17g}]", i ? ", " : "", region.polygon[i].x,
                             region.polygon[i].y);
        y += "]\n";
    }
    if (!set.background.empty()) y += "background: " + quoted(set.background) + "\n";
    if (!set.noise_region.empty()) y += "noise_region: " + quoted(set.noise_region) + "\n";
    return y;
}

RegionSet parse_regions(const ConfigNode& root) {
    if (!root.is_map())
        root.fail(
            "expected a mapping with 'regions' (and optionally 'background', 'noise_region')");
    root.check_keys({"regions", "background", "noise_region"});
    RegionSet set;
    const ConfigNode list = root.at("regions");
    const auto items = list.elements();
    if (items.empty()) list.fail("expected at least one region");
    std::set<std::string> names;
    for (const auto& item : items) {
        if (!item.is_map()) item.fail("expected a mapping with 'name' and 'polygon'");
        item.check_keys({"name", "polygon"});
        Region region;
        region.name = item.get<std::string>("name");
        region.location = item.location() + ": " + item.path();
        if (region.name.empty()) item.at("name").fail("expected a non-empty region name");
        if (!names.insert(region.name).second)
            item.at("name").fail(fmt::format("duplicate region name '{}'", region.name));
        const ConfigNode polygon = item.at("polygon");
        for (const auto& vertex : polygon.elements()) region.polygon.push_back(parse_point(vertex));
        if (region.polygon.size() < 3)
            polygon.fail(
                fmt::format("expected a polygon of at least 3 vertices [[x, y], ...], got {}",
                            region.polygon.size()));
        set.regions.push_back(std::move(region));
    }
    auto named_region = [&](std::string_view key) -> std::string {
        const auto node = root.find(key);
        if (!node) return {};
        auto name = node->as<std::string>();
        if (!names.count(name)) {
            std::vector<std::string> all(names.begin(), names.end());
            const auto hint = closest_match(name, all);
            node->fail(fmt::format("'{}' names no region{}", name,
                                   hint.empty() ? "" : " (did you mean '" + hint + "'?)"));
        }
        return name;
    };
    set.background = named_region("background");
    set.noise_region = named_region("noise_region");
    return set;
}

RegionSet load_regions(const std::filesystem::path& path) {
    return parse_regions(ConfigNode::load_file(path));
}

std::vector<std::uint8_t> region_mask(const Region& region, int width, int height) {
    std::vector<cv::Point2f> contour;
    double x_lo = width, x_hi = -1, y_lo = height, y_hi = -1;
    for (const auto& p : region.polygon) {
        if (p.x < -0.5 || p.y < -0.5 || p.x > width - 0.5 || p.y > height - 0.5)
            fail(
                "{}: region '{}' has vertex ({}, {}) outside the {}×{} measured image (x in [0, "
                "{}], y in [0, {}])",
                region.location, region.name, p.x, p.y, width, height, width - 1, height - 1);
        contour.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
        x_lo = std::min(x_lo, p.x);
        x_hi = std::max(x_hi, p.x);
        y_lo = std::min(y_lo, p.y);
        y_hi = std::max(y_hi, p.y);
    }
    double twice_area = 0.0;  // shoelace formula
    for (std::size_t i = 0; i < region.polygon.size(); ++i) {
        const auto& a = region.polygon[i];
        const auto& b = region.polygon[(i + 1) % region.polygon.size()];
        twice_area += a.x * b.y - b.x * a.y;
    }
    if (std::abs(twice_area) < 1e-9)
        fail("{}: region '{}' is empty: its polygon has zero area (collinear or repeated vertices)",
             region.location, region.name);
    // A pixel belongs to the region when its centre is inside the polygon or on its edge.
    std::vector<std::uint8_t> mask(
        static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
    std::size_t count = 0;
    for (int y = std::max(0, static_cast<int>(std::ceil(y_lo)));
         y <= std::min(height - 1, static_cast<int>(std::floor(y_hi))); ++y)
        for (int x = std::max(0, static_cast<int>(std::ceil(x_lo)));
             x <= std::min(width - 1, static_cast<int>(std::floor(x_hi))); ++x)
            if (cv::pointPolygonTest(contour,
                                     cv::Point2f(static_cast<float>(x), static_cast<float>(y)),
                                     false) >= 0) {
                mask[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                     static_cast<std::size_t>(x)] = 1;
                ++count;
            }
    if (count == 0)
        fail("{}: region '{}' covers no pixel centre of the image", region.location, region.name);
    return mask;
}

Region whole_image_region(int width, int height) {
    const double w = width - 1, h = height - 1;
    return {"image", {{0, 0}, {w, 0}, {w, h}, {0, h}}, "whole image"};
}

}  // namespace tirpol::report
