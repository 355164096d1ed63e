#include "tirpol/core/path_info.h"

#include <fmt/printf.h>

#include <cmath>
#include <filesystem>

#include "tirpol/core/exr_io.h"
#include "tirpol/core/utf8.h"

namespace tirpol {

namespace {
nlohmann::json attribute_json(const AttributeValue& v) {
    return std::visit([](const auto& x) { return nlohmann::json(x); }, v);
}

std::string attribute_text(const AttributeValue& v) {
    return std::visit(
        [](const auto& x) -> std::string {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, std::string>)
                return "\"" + x + "\"";
            else if constexpr (std::is_same_v<T, std::vector<double>>)
                return json_text(nlohmann::json(x));
            else
                return fmt::format("{}", x);
        },
        v);
}

nlohmann::json finite_or_null(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}
}  // namespace

PathInfo describe_path(const std::string& path) {
    PathInfo info{path, std::nullopt, std::nullopt};
    if (std::filesystem::is_directory(path)) {
        info.session = summarize_session(read_session(path));
        return info;
    }
    const Image image = read_exr(path);
    ImageInfo& i = info.image.emplace();
    i.width = image.width();
    i.height = image.height();
    i.attributes = image.attributes();
    for (const auto& name : image.channel_names())
        i.channels.emplace_back(name, channel_stats(image.channel(name)));
    return info;
}

nlohmann::json path_info_json(const PathInfo& info) {
    if (info.session) {
        nlohmann::json out = session_summary_to_json(*info.session);
        out["session"] = info.path;
        return out;
    }
    const ImageInfo& image = *info.image;
    nlohmann::json out;
    out["file"] = info.path;
    out["width"] = image.width;
    out["height"] = image.height;
    for (const auto& [name, value] : image.attributes)
        out["attributes"][name] = attribute_json(value);
    for (const auto& [name, s] : image.channels)
        out["channels"][name] = {{"min", finite_or_null(s.min)}, {"mean", finite_or_null(s.mean)},
                                 {"max", finite_or_null(s.max)}, {"std", finite_or_null(s.std)},
                                 {"nan_count", s.nan_count},     {"inf_count", s.inf_count}};
    return out;
}

std::string path_info_text(const PathInfo& info) {
    if (info.session) return session_summary_text(*info.session, info.path);
    const ImageInfo& image = *info.image;
    std::string text = fmt::sprintf("%s: %d × %d, %zu channel(s)\n", info.path, image.width,
                                    image.height, image.channels.size());
    if (!image.attributes.empty()) text += "attributes:\n";
    for (const auto& [name, value] : image.attributes)
        text += fmt::sprintf("  %-28s %s\n", name, attribute_text(value));
    text += fmt::sprintf("%-12s %14s %14s %14s %12s %8s\n", "channel", "min", "mean", "max", "std",
                         "NaN");
    for (const auto& [name, s] : image.channels)
        text += fmt::sprintf("%-12s %14.6g %14.6g %14.6g %12.4g %8zu\n", name, s.min, s.mean, s.max,
                             s.std, s.nan_count);
    return text;
}

}  // namespace tirpol
