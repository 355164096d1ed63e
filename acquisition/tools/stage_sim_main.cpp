// tirpol-stage-sim: a Thorlabs APT or Elliptec rotation stage on a pseudo-terminal, for tests and
// for trying tirpol without hardware. Prints the device path on the first line of stdout.
//
//   tirpol-stage-sim --protocol apt|elliptec [--link PATH] [--fault
//   no-reply|busy|error|disconnect-mid-move]
//                    [--fault-on-move N] [--move-deg-per-s V] [--address A]
//                    [--backlash-deg B] [--lost-step-probability P --lost-step-deg L] [--seed S]
//                    [--encoder-error-deg E]

#include <cstdio>
#include <cstdlib>
#include <string>

#include "tirpol/acquisition/sim/stage_simulator.h"

namespace {

[[noreturn]] void usage(const char* message) {
    std::fprintf(
        stderr,
        "tirpol-stage-sim: %s\n"
        "usage: tirpol-stage-sim --protocol apt|elliptec [--link PATH]\n"
        "       [--fault none|no-reply|busy|error|disconnect-mid-move] [--fault-on-move N]\n"
        "       [--move-deg-per-s V] [--address 0-F] [--backlash-deg B]\n"
        "       [--lost-step-probability P] [--lost-step-deg L] [--seed S]\n"
        "       [--encoder-error-deg E]\n",
        message);
    std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
    using namespace tirpol::acquisition;
    StageSimulatorOptions options;
    bool have_protocol = false, speed_given = false;
    std::string link;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(("missing value after " + arg).c_str());
            return argv[++i];
        };
        if (arg == "--protocol") {
            const auto p = parse_sim_protocol(value());
            if (!p) usage("--protocol: expected apt or elliptec");
            options.protocol = *p;
            have_protocol = true;
        } else if (arg == "--fault") {
            const auto f = parse_sim_fault(value());
            if (!f) usage("--fault: expected none, no-reply, busy, error or disconnect-mid-move");
            options.fault = *f;
        } else if (arg == "--fault-on-move") {
            options.fault_on_move = std::atoi(value().c_str());
            if (options.fault_on_move < 1) usage("--fault-on-move: expected an integer ≥ 1");
        } else if (arg == "--move-deg-per-s") {
            options.deg_per_s = std::atof(value().c_str());
            if (!(options.deg_per_s > 0)) usage("--move-deg-per-s: expected a positive speed");
            speed_given = true;
        } else if (arg == "--address") {
            const std::string a = value();
            if (a.size() != 1) usage("--address: expected one hex digit");
            options.elliptec_address = a[0];
        } else if (arg == "--backlash-deg" || arg == "--lost-step-deg" ||
                   arg == "--encoder-error-deg") {
            const double v = std::atof(value().c_str());
            if (!(v >= 0 && v < 90)) usage((arg + ": expected degrees in [0, 90)").c_str());
            (arg == "--backlash-deg"    ? options.backlash_deg
             : arg == "--lost-step-deg" ? options.lost_step_deg
                                        : options.encoder_error_deg) = v;
        } else if (arg == "--lost-step-probability") {
            options.lost_step_probability = std::atof(value().c_str());
            if (!(options.lost_step_probability >= 0 && options.lost_step_probability <= 1))
                usage("--lost-step-probability: expected a probability in [0, 1]");
        } else if (arg == "--seed") {
            options.seed = static_cast<std::uint32_t>(std::strtoul(value().c_str(), nullptr, 10));
        } else if (arg == "--link") {
            link = value();
        } else if (arg == "-h" || arg == "--help") {
            usage("help");
        } else {
            usage(("unknown argument " + arg).c_str());
        }
    }
    if (!have_protocol) usage("--protocol is required");
    // Realistic defaults: a K10CR1 turns at up to 10°/s; an ELL14 about 360°/s for short moves.
    if (!speed_given) options.deg_per_s = options.protocol == SimProtocol::Apt ? 10.0 : 360.0;

    StageSimulator simulator(options);
    return run_pty_simulator_program(simulator, link, "tirpol-stage-sim");
}
