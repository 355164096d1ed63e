#include "numeric_options.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <utility>

#include "cli.h"
#include "tirpol/core/limits.h"

namespace tirpol::cli {

namespace {
namespace lim = ::tirpol::limits;

// Option ranges by long name, in every subcommand that has the option ("*"), or in one subcommand.
// Each range comes from core/limits.h, which the libraries check too; docs/cli.md lists this table.
const std::map<std::pair<std::string, std::string>, OptionLimit>& limit_table() {
    static const std::map<std::pair<std::string, std::string>, OptionLimit> table = {
        {{"*", "--band-um"},
         {lim::kMinWavelengthUm, lim::kMaxWavelengthUm,
          "a wavelength in micrometres (0.1 µm far UV to 1 mm)"}},
        {{"*", "--wavelength-um"},
         {lim::kMinWavelengthUm, lim::kMaxWavelengthUm,
          "a wavelength in micrometres (0.1 µm far UV to 1 mm)"}},
        {{"*", "--temperature-k"},
         {lim::kMinTemperatureK, lim::kMaxTemperatureK, "a physical temperature in kelvin"}},
        {{"*", "--fpa-temperature-k"},
         {lim::kMinTemperatureK, lim::kMaxTemperatureK, "a physical temperature in kelvin"}},
        {{"*", "--spp"}, {1, lim::kMaxSamplesPerPixel, "samples per pixel"}},
        {{"*", "--width"}, {1, lim::kMaxImageSide, "an image side in pixels"}},
        {{"*", "--height"}, {1, lim::kMaxImageSide, "an image side in pixels"}},
        {{"fit", "--starts"}, {1, lim::kMaxFitStarts, "the number of fit starts"}},
        {{"*", "--frames-per-angle"}, {1, lim::kMaxFramesPerStep, "frames per polarizer angle"}},
        {{"flir-temperature", "--emissivity"},
         {lim::kMinCorrectionEmissivity, 1.0,
          "an emissivity the correction can divide by (below 0.01 the reflected term dominates)"}},
        {{"flir-temperature", "--window-transmission"},
         {lim::kMinCorrectionEmissivity, 1.0,
          "a window transmission the correction can divide by"}},
    };
    return table;
}

bool is_numeric(const CLI::Option& option) {
    const std::string type = option.get_type_name();
    return type.find("FLOAT") != std::string::npos || type.find("INT") != std::string::npos ||
           type.find("NUMBER") != std::string::npos;
}

std::string long_name(const CLI::Option& option) {
    const auto& names = option.get_lnames();
    return names.empty() ? option.get_name() : "--" + names.front();
}

// The number in `text` if all of it is one (strtod's syntax, as CLI11's conversion accepts), else
// nullopt: CLI11 then reports the malformed value itself.
std::optional<double> number_in(const std::string& text) {
    if (text.empty()) return std::nullopt;
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size()) return std::nullopt;
    if (errno == ERANGE && std::isinf(value))
        return value;  // overflow: refused below as not finite
    return value;
}

CLI::Validator numeric_validator(const OptionLimit* limit) {
    // An empty description keeps --help unchanged; docs/cli.md lists the ranges.
    return CLI::Validator(
        [limit](std::string& text) -> std::string {
            const std::optional<double> value = number_in(text);
            if (!value) return {};
            if (!std::isfinite(*value))
                return fmt::format("expected a finite number, got '{}'", text);
            if (limit && !(*value >= limit->lo && *value <= limit->hi))
                return fmt::format("{} is outside [{}, {}], {} (limits table in docs/cli.md)", text,
                                   limit->lo, limit->hi, limit->why);
            return {};
        },
        "", "finite number");
}

void validate_recursively(CLI::App& app, const std::string& path) {
    for (CLI::Option* option : app.get_options()) {
        if (!is_numeric(*option) || option->get_expected_max() == 0) continue;
        // transform() puts the check first, before an option's own range check ("Value nan not in
        // range"), so every numeric option refuses nan and inf with the same message.
        option->transform(numeric_validator(option_limit(path, long_name(*option))));
    }
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        validate_recursively(*sub, path.empty() ? sub->get_name() : path + " " + sub->get_name());
}
}  // namespace

const OptionLimit* option_limit(const std::string& subcommand, const std::string& name) {
    const auto& table = limit_table();
    if (const auto it = table.find({subcommand, name}); it != table.end()) return &it->second;
    if (const auto it = table.find({"*", name}); it != table.end()) return &it->second;
    return nullptr;
}

void validate_numeric_options(CLI::App& app) { validate_recursively(app, ""); }

double parse_finite_number(const std::string& text, const std::string& option) {
    const std::optional<double> value = number_in(text);
    if (!value) usage_error(option, "\"{}\" is not a number", text);
    if (!std::isfinite(*value)) usage_error(option, "expected a finite number, got '{}'", text);
    return *value;
}

}  // namespace tirpol::cli
