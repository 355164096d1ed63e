#include <cmath>
#include <optional>
#include <string>

#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/fitting/fit_run.h"

namespace tirpol::fitting {

namespace {
// All of `text` as one finite number (the CLI's numeric options' parser).
double finite_number(std::string_view text, std::string_view item) {
    const std::optional<double> value = parse_number(text);
    if (!value) fail("{}: \"{}\" is not a number", item, text);
    if (!std::isfinite(*value)) fail("{}: expected a finite number, got '{}'", item, text);
    return *value;
}

ParameterSetting& setting_of(std::string_view name, ParameterSettings& settings) {
    return settings[static_cast<std::size_t>(parameter_from_name(name))];
}
}  // namespace

void apply_parameter_bound(std::string_view item, ParameterSettings& settings) {
    const auto eq = item.find('='), colon = item.find(':');
    if (eq == std::string_view::npos || colon == std::string_view::npos || colon < eq)
        fail("{}: expected NAME=LOWER:UPPER, e.g. sigma=0.05:0.8", item);
    ParameterSetting& s = setting_of(item.substr(0, eq), settings);
    s.lower = finite_number(item.substr(eq + 1, colon - eq - 1), item);
    s.upper = finite_number(item.substr(colon + 1), item);
}

void apply_parameter_fix(std::string_view item, ParameterSettings& settings) {
    const auto eq = item.find('=');
    ParameterSetting& s = setting_of(item.substr(0, eq), settings);
    s.fixed = true;
    if (eq != std::string_view::npos) s.initial = finite_number(item.substr(eq + 1), item);
}

void apply_parameter_free(std::string_view name, ParameterSettings& settings) {
    setting_of(name, settings).fixed = false;
}

}  // namespace tirpol::fitting
