#pragma once
// The `tirpol acquire` command line the CLI tests run: a plan, a simulated camera, the stage
// simulator on the pseudo-terminal `DIR/stage`, the session in `DIR/session`, no prompts.

#include <filesystem>
#include <string>
#include <vector>

namespace tirpol::test {

inline std::vector<std::string> acquire_cli_args(const std::filesystem::path& dir,
                                                 const std::filesystem::path& plan,
                                                 const std::string& camera_uri, bool resume) {
    std::vector<std::string> args{TIRPOL_CLI_PATH,
                                  "acquire",
                                  plan.string(),
                                  "--camera",
                                  camera_uri,
                                  "--stage",
                                  "thorlabs-apt://" + (dir / "stage").string(),
                                  "-o",
                                  (dir / "session").string(),
                                  "--non-interactive"};
    if (resume) args.push_back("--resume");
    return args;
}

}  // namespace tirpol::test
