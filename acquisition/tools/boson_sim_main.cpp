// tirpol-boson-sim: the control link of a FLIR Boson core (FSLP over its CDC-ACM port) on a
// pseudo-terminal, for tests and for trying tirpol without hardware. Prints the device path on the
// first line of stdout; open it with `boson://<path>` (tirpol acquire --camera-control). The video
// of this core is not served (a separate process cannot share it with a sim:// camera): FFCs run
// and are reported, frames are untouched.

#include <cstdio>
#include <cstdlib>
#include <string>

#include "tirpol/acquisition/internal/boson_simulator.h"
#include "tirpol/core/error.h"

namespace {

[[noreturn]] void usage(const char* message) {
    std::fprintf(
        stderr,
        "tirpol-boson-sim: %s\n"
        "usage: tirpol-boson-sim [--link PATH] [--fpa-k K] [--drift-k-per-s R] [--threshold-k K]\n"
        "       [--ffc-s S] [--fault none|drop-reply|corrupt-crc|wrong-sequence|silent] "
        "[--fault-on N]\n",
        message);
    std::exit(2);
}

std::string value_after(int& i, int argc, char** argv) {
    if (i + 1 >= argc) usage((std::string("missing value after ") + argv[i]).c_str());
    return argv[++i];
}

double number(const std::string& flag, const std::string& text) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0') usage((flag + ": expected a number").c_str());
    return v;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace tirpol::acquisition;
    BosonCoreConfig core;
    BosonSimulatorOptions options;
    std::string link;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&] { return value_after(i, argc, argv); };
        if (arg == "--link")
            link = value();
        else if (arg == "--fpa-k")
            core.fpa_start_k = number(arg, value());
        else if (arg == "--drift-k-per-s")
            core.fpa_drift_k_per_s = number(arg, value());
        else if (arg == "--threshold-k")
            core.ffc_threshold_k = number(arg, value());
        else if (arg == "--ffc-s")
            core.ffc_duration_s = number(arg, value());
        else if (arg == "--fault-on") {
            options.fault_on_command = std::atoi(value().c_str());
            if (options.fault_on_command < 1) usage("--fault-on: expected an integer ≥ 1");
        } else if (arg == "--fault") {
            const std::string f = value();
            if (f == "none")
                options.fault = BosonSimFault::None;
            else if (f == "drop-reply")
                options.fault = BosonSimFault::DropReply;
            else if (f == "corrupt-crc")
                options.fault = BosonSimFault::CorruptCrc;
            else if (f == "wrong-sequence")
                options.fault = BosonSimFault::WrongSequence;
            else if (f == "silent")
                options.fault = BosonSimFault::Silent;
            else
                usage("--fault: expected none, drop-reply, corrupt-crc, wrong-sequence or silent");
        } else if (arg == "-h" || arg == "--help") {
            usage("help");
        } else {
            usage(("unknown argument " + arg).c_str());
        }
    }
    try {
        BosonSimulator simulator(std::make_shared<BosonCoreModel>(core), options);
        return run_pty_simulator_program(simulator, link, "tirpol-boson-sim");
    } catch (const tirpol::Error& e) {
        std::fprintf(stderr, "tirpol-boson-sim: %s\n", e.what());
        return 2;
    }
}
