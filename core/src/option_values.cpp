#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <utility>

#include "tirpol/core/limits.h"

namespace tirpol {

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
}  // namespace

std::optional<double> parse_number(std::string_view text) {
    if (text.empty()) return std::nullopt;
    const std::string s(text);
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(s.c_str(), &end);
    if (end != s.c_str() + s.size()) return std::nullopt;
    return value;  // an overflow is ±inf (ERANGE), which callers refuse as not finite
}

const OptionLimit* option_limit(const std::string& subcommand, const std::string& long_name) {
    const auto& table = limit_table();
    if (const auto it = table.find({subcommand, long_name}); it != table.end()) return &it->second;
    if (const auto it = table.find({"*", long_name}); it != table.end()) return &it->second;
    return nullptr;
}

std::string option_number_problem(const std::string& text, const OptionLimit* limit) {
    const std::optional<double> value = parse_number(text);
    if (!value) return {};
    if (!std::isfinite(*value)) return fmt::format("expected a finite number, got '{}'", text);
    if (limit && !(*value >= limit->lo && *value <= limit->hi))
        return fmt::format("{} is outside [{}, {}], {} (limits table in docs/cli.md)", text,
                           limit->lo, limit->hi, limit->why);
    return {};
}

}  // namespace tirpol
