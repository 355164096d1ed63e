#include "common_options.h"

#include <cstdio>

#include "tirpol/core/utf8.h"

namespace tirpol::cli {

CLI::Option* add_json_flag(CLI::App* command, bool& json, const std::string& description) {
    return command->add_flag("--json", json, description);
}

CLI::Option* add_output_option(CLI::App* command, std::string& output,
                               const std::string& description) {
    return command->add_option("-o,--output", output, description)->required();
}

CLI::Option* add_band_options(CLI::App* command, std::vector<double>& band_um, std::string& rsr) {
    CLI::Option* band =
        command->add_option("--band-um", band_um, "Band limits LO HI in micrometres")->expected(2);
    command->add_option("--rsr", rsr, "Relative spectral response CSV (wavelength_um,response)")
        ->check(CLI::ExistingFile);
    return band;
}

void print_json(const nlohmann::json& json) { std::printf("%s\n", json_text(json, 2).c_str()); }

void print_text(const std::string& text) { std::fputs(text.c_str(), stdout); }

}  // namespace tirpol::cli
