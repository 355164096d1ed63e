// `tirpol fit` reads the emissivity CSV through core's one reader: the current layout (frame
// column, 1σ *_std columns) and the older ones (hand-written 1σ, extract-emissivity's 2σ without a
// frame) carry the same measurement, so they must give the same fitted material, number for number.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <sstream>

#include "cli_runner.h"
#include "test_support.h"
#include "tirpol/core/atomic_file.h"

namespace {

using tirpol::test::run_cli;

// (angle, ε_S0, ε_S1) of a paint-like curve; σ(ε_S0) = 0.003, σ(ε_S1) = 0.002.
constexpr double kRows[][3] = {{0, 0.962, 0.0},    {20, 0.961, -0.0012}, {40, 0.957, -0.006},
                               {60, 0.94, -0.019}, {70, 0.915, -0.033},  {80, 0.84, -0.056}};

// The fitted values of a material file: its refractive_index and parameters lines (source and notes
// name the input file, so they differ by design).
std::string fitted_values(const std::filesystem::path& yaml) {
    std::istringstream in(tirpol::read_file(yaml));
    std::string out, line;
    bool in_parameters = false;
    while (std::getline(in, line)) {
        if (line.rfind("refractive_index:", 0) == 0) out += line + '\n';
        if (in_parameters && line.rfind("  ", 0) == 0) out += line + '\n';
        in_parameters = in_parameters || line == "parameters:";
    }
    return out;
}

std::string fit(const std::filesystem::path& csv) {
    const auto yaml = csv.parent_path() / (csv.stem().string() + ".yaml");
    const auto r =
        run_cli("fit " + csv.string() + " --wavelength-um 10 --starts 2 -o " + yaml.string());
    EXPECT_EQ(r.exit_code, 0) << r.out;
    return fitted_values(yaml);
}

TEST(EmissivityCsvCli, CurrentAndOlderLayoutsFitTheSame) {
    tirpol::test::TempDir dir;
    std::string current =
        "name,view_angle_deg,temperature_k,pixels,l_dw_w_m2_sr,l_bb_w_m2_sr,frame,eps_s0,eps_s0_"
        "std,eps_s1,"
        "eps_s1_std,eps_s2,eps_s2_std,wavelength_um\n";
    std::string hand_written = "angle_deg,e_s0,e_s0_sigma,e_s1,e_s1_sigma\n";
    std::string two_sigma =
        "name,view_angle_deg,temperature_k,pixels,l_dw_w_m2_sr,l_bb_w_m2_sr,eps_s0,eps_s0_2sigma,"
        "eps_s1,"
        "eps_s1_2sigma,eps_s2,eps_s2_2sigma\n";
    for (const auto& [angle, s0, s1] : kRows) {
        current +=
            fmt::format("p{0},{0},,,,,plane_of_emission,{1},0.003,{2},0.002,,,\n", angle, s0, s1);
        hand_written += fmt::format("{},{},0.003,{},0.002\n", angle, s0, s1);
        two_sigma +=
            fmt::format("p{0},{0},300,100,5,40,{1},0.006,{2},0.004,0,0.004\n", angle, s0, s1);
    }
    tirpol::test::write_text(dir / "current.csv", current);
    tirpol::test::write_text(dir / "hand.csv", hand_written);
    tirpol::test::write_text(dir / "two_sigma.csv", two_sigma);
    const std::string reference = fit(dir / "current.csv");
    ASSERT_NE(reference.find("sigma:"), std::string::npos) << reference;
    EXPECT_EQ(fit(dir / "hand.csv"), reference);
    EXPECT_EQ(fit(dir / "two_sigma.csv"), reference);

    // An unknown frame is refused with the file, line and the accepted values.
    tirpol::test::write_text(dir / "bad.csv",
                             "view_angle_deg,frame,eps_s0,eps_s0_std,eps_s1,eps_s1_std\n"
                             "30,camera,0.95,0.003,-0.01,0.002\n");
    const auto r =
        run_cli("fit " + (dir / "bad.csv").string() + " -o " + (dir / "bad.yaml").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.out.find("bad.csv:2"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("plane_of_emission"), std::string::npos) << r.out;
}

}  // namespace
