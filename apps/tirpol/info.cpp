// `tirpol info FILE.exr`: size, channels, header attributes and per-channel statistics.

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/utf8.h"

namespace tirpol::cli {

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

void run_info(const std::string& path, bool json) {
    const Image image = read_exr(path);
    nlohmann::json out;
    out["file"] = path;
    out["width"] = image.width();
    out["height"] = image.height();
    for (const auto& [name, value] : image.attributes())
        out["attributes"][name] = attribute_json(value);
    for (const auto& name : image.channel_names()) {
        const ChannelStats s = channel_stats(image.channel(name));
        out["channels"][name] = {{"min", finite_or_null(s.min)}, {"mean", finite_or_null(s.mean)},
                                 {"max", finite_or_null(s.max)}, {"std", finite_or_null(s.std)},
                                 {"nan_count", s.nan_count},     {"inf_count", s.inf_count}};
    }
    if (json) {
        std::printf("%s\n", json_text(out, 2).c_str());
        return;
    }
    std::printf("%s: %d × %d, %zu channel(s)\n", path.c_str(), image.width(), image.height(),
                image.channel_names().size());
    if (!image.attributes().empty()) std::printf("attributes:\n");
    for (const auto& [name, value] : image.attributes())
        std::printf("  %-28s %s\n", name.c_str(), attribute_text(value).c_str());
    std::printf("%-12s %14s %14s %14s %12s %8s\n", "channel", "min", "mean", "max", "std", "NaN");
    for (const auto& name : image.channel_names()) {
        const ChannelStats s = channel_stats(image.channel(name));
        std::printf("%-12s %14.6g %14.6g %14.6g %12.4g %8zu\n", name.c_str(), s.min, s.mean, s.max,
                    s.std, s.nan_count);
    }
}
}  // namespace

namespace {
void register_info(CLI::App& app) {
    auto path = std::make_shared<std::string>();
    auto json = std::make_shared<bool>(false);
    auto* cmd =
        app.add_subcommand("info", "Describe an EXR image: size, channels, header, statistics");
    cmd->add_option("FILE", *path, "OpenEXR file")->required();
    cmd->add_flag("--json", *json, "Print JSON");
    cmd->callback([path, json] { run_info(*path, *json); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(10, register_info);

}  // namespace tirpol::cli
