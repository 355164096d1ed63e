#include "numeric_options.h"

#include "tirpol/core/limits.h"

namespace tirpol::cli {

namespace {
bool is_numeric(const CLI::Option& option) {
    const std::string type = option.get_type_name();
    return type.find("FLOAT") != std::string::npos || type.find("INT") != std::string::npos ||
           type.find("NUMBER") != std::string::npos;
}

std::string long_name(const CLI::Option& option) {
    const auto& names = option.get_lnames();
    return names.empty() ? option.get_name() : "--" + names.front();
}

void validate_recursively(CLI::App& app, const std::string& path) {
    for (CLI::Option* option : app.get_options()) {
        if (!is_numeric(*option) || option->get_expected_max() == 0) continue;
        const OptionLimit* limit = option_limit(path, long_name(*option));
        // transform() puts the check first, before an option's own range check ("Value nan not in
        // range"), so every numeric option refuses nan and inf with the same message. An empty
        // description keeps --help unchanged; docs/cli.md lists the ranges.
        option->transform(CLI::Validator(
            [limit](std::string& text) { return option_number_problem(text, limit); }, "",
            "finite number"));
    }
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        validate_recursively(*sub, path.empty() ? sub->get_name() : path + " " + sub->get_name());
}
}  // namespace

void validate_numeric_options(CLI::App& app) { validate_recursively(app, ""); }

}  // namespace tirpol::cli
