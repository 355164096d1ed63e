#include "temperature_value.h"

#include <charconv>
#include <string>

#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::simulation {

namespace {
std::string trim(std::string s) {
    const auto first = s.find_first_not_of(" \t");
    const auto last = s.find_last_not_of(" \t");
    return first == std::string::npos ? std::string() : s.substr(first, last - first + 1);
}

bool parse_number(const std::string& text, double& out) {
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, out);
    return ec == std::errc() && ptr == end;
}
}  // namespace

double temperature_k_from_config(const ConfigNode& node) {
    if (!node.is_scalar())
        node.fail(
            "expected a temperature: a number in K, or a string like \"15 °C\" or \"288.15 K\"");
    const std::string text = trim(node.as<std::string>());
    double value = 0.0, kelvin = 0.0;
    if (parse_number(text, value)) {
        kelvin = value;
    } else if (text.size() > 3 && text.ends_with("°C") &&
               parse_number(trim(text.substr(0, text.size() - 3)), value)) {
        kelvin = value + kZeroCelsiusK;
    } else if (text.size() > 1 && text.ends_with("K") &&
               parse_number(trim(text.substr(0, text.size() - 1)), value)) {
        kelvin = value;
    } else {
        node.fail(
            "expected a temperature: a number in K, or a string like \"15 °C\" or \"288.15 K\", "
            "got \"" +
            text + "\"");
    }
    if (!(kelvin >= limits::kMinTemperatureK && kelvin <= limits::kMaxTemperatureK))
        node.fail(fmt::format("temperature {} K is outside the physical range [{}, {}] K", kelvin,
                              limits::kMinTemperatureK, limits::kMaxTemperatureK));
    return kelvin;
}

}  // namespace tirpol::simulation
