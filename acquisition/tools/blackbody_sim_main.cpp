// tirpol-blackbody-sim: a Fluke 4180/4181 infrared calibrator (blackbody) controller on a
// pseudo-terminal, for tests and for trying tirpol without hardware. Prints the device path on the
// first line of stdout; open it with `fluke-4180://<path>` (docs/acquisition-blackbody.md).

#include <cstdio>
#include <cstdlib>
#include <string>

#include "tirpol/acquisition/internal/blackbody_simulator.h"
#include "tirpol/core/error.h"

namespace {

[[noreturn]] void usage(const char* message) {
    std::fprintf(
        stderr,
        "tirpol-blackbody-sim: %s\n"
        "usage: tirpol-blackbody-sim [--model 4180|4181] [--link PATH] [--tau-s S] [--ambient-k "
        "K]\n"
        "       [--noise-k K] [--limit-k K] [--window-s S] [--sample-period-s S]\n"
        "       [--fault none|over-temperature|no-reply|garbled] [--fault-on-set N] [--seed N]\n",
        message);
    std::exit(2);
}

/// The argument after argv[i] (advancing i), or usage() when there is none.
std::string value_after(int& i, int argc, char** argv) {
    if (i + 1 >= argc) usage((std::string("missing value after ") + argv[i]).c_str());
    return argv[++i];
}

double positive(const std::string& flag, const std::string& text) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || !(v >= 0.0))
        usage((flag + ": expected a number ≥ 0").c_str());
    return v;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace tirpol::acquisition;
    BlackbodySimulatorOptions options;
    std::string link;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&] { return value_after(i, argc, argv); };
        if (arg == "--model")
            options.model = value();
        else if (arg == "--link")
            link = value();
        else if (arg == "--tau-s")
            options.time_constant_s = positive(arg, value());
        else if (arg == "--ambient-k")
            options.ambient_k = positive(arg, value());
        else if (arg == "--noise-k")
            options.noise_k = positive(arg, value());
        else if (arg == "--limit-k")
            options.stability_limit_k = positive(arg, value());
        else if (arg == "--window-s")
            options.stability_window_s = positive(arg, value());
        else if (arg == "--sample-period-s")
            options.sample_period_s = positive(arg, value());
        else if (arg == "--seed")
            options.seed = static_cast<std::uint64_t>(positive(arg, value()));
        else if (arg == "--fault-on-set") {
            options.fault_on_set = std::atoi(value().c_str());
            if (options.fault_on_set < 1) usage("--fault-on-set: expected an integer ≥ 1");
        } else if (arg == "--fault") {
            const auto f = parse_blackbody_fault(value());
            if (!f) usage("--fault: expected none, over-temperature, no-reply or garbled");
            options.fault = *f;
        } else if (arg == "-h" || arg == "--help") {
            usage("help");
        } else {
            usage(("unknown argument " + arg).c_str());
        }
    }
    try {
        BlackbodySimulator simulator(options);
        return run_pty_simulator_program(simulator, link, "tirpol-blackbody-sim");
    } catch (const tirpol::Error& e) {
        usage(e.what());
    }
}
