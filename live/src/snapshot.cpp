#include "snapshot.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <type_traits>

#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/quicklook.h"

namespace tirpol::live {

namespace {
bool is_std_channel(const std::string& name) {
    return name.size() > 4 && name.compare(name.size() - 4, 4, "_std") == 0;
}

std::string attribute_text(const AttributeValue& value) {
    return std::visit(
        [](const auto& v) -> std::string {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, std::string>) {
                return v;
            } else if constexpr (std::is_same_v<T, std::vector<double>>) {
                return fmt::format("{}", fmt::join(v, ","));
            } else {
                return fmt::format("{}", v);
            }
        },
        value);
}
}  // namespace

std::vector<std::pair<std::string, std::string>> snapshot_text(const Image& image) {
    std::vector<std::pair<std::string, std::string>> text;
    if (const auto it = image.attributes().find("time_utc"); it != image.attributes().end())
        text.emplace_back("Creation Time", attribute_text(it->second));
    for (const auto& [name, value] : image.attributes())
        text.emplace_back("tirpol." + name, attribute_text(value));
    return text;
}

SnapshotFiles write_snapshot(const std::filesystem::path& folder, const std::string& stem,
                             const Image& image, const std::string& units, bool force) {
    SnapshotFiles files;
    files.exr = stem + ".exr";
    for (const std::string& name : image.channel_names())
        if (!is_std_channel(name)) files.pngs.push_back(stem + "_" + name + ".png");
    if (!force) {
        std::vector<std::string> names = files.pngs;
        names.push_back(files.exr);
        for (const std::string& name : names)
            if (std::filesystem::exists(folder / name))
                fail("snapshot: {} exists; start tirpol live with --force to replace it",
                     (folder / name).string());
    }
    write_exr(folder / files.exr, image);
    const auto text = snapshot_text(image);
    for (const std::string& name : image.channel_names()) {
        if (is_std_channel(name)) continue;
        // The live frame's S0 beside a cycle is drawn as S0 is.
        const std::string quantity = name == "live_S0" ? "S0" : name;
        QuicklookOptions options = channel_quicklook_options(quantity, units);
        options.title = name;
        options.text = text;
        write_quicklook(folder / (stem + "_" + name + ".png"), image.channel(name), image.width(),
                        image.height(), options);
    }
    return files;
}

}  // namespace tirpol::live
