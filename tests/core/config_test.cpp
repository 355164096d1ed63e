// YAML configuration: typed access and errors that name the file, line, field, value and
// expectation.

#include "tirpol/core/config.h"

#include <gtest/gtest.h>

#include "error_of.h"
#include "test_support.h"
#include "tirpol/core/error.h"

using tirpol::test::error_of;

namespace tirpol {
namespace {

constexpr const char* kScene = R"(camera:
  fov_deg: 30
  resolution: [640, 512]
sky:
  type: clear
objects:
  - name: panel
    temperature_k: 290.5
)";

TEST(Config, TypedAccessors) {
    const auto root = ConfigNode::parse(kScene, "scene.yaml");
    EXPECT_DOUBLE_EQ(root.at("camera").get<double>("fov_deg"), 30.0);
    EXPECT_EQ(root.at("camera").get<std::vector<double>>("resolution"),
              (std::vector<double>{640, 512}));
    EXPECT_EQ(root.at("sky").get<std::string>("type"), "clear");
    EXPECT_DOUBLE_EQ(root.at("objects").elements()[0].get<double>("temperature_k"), 290.5);
    EXPECT_EQ(root.at("sky").get_or<int>("samples", 8), 8);
    EXPECT_EQ(root.keys(), (std::vector<std::string>{"camera", "sky", "objects"}));
}

TEST(Config, WrongTypeNamesFileLineFieldValueAndExpectation) {
    const auto root = ConfigNode::parse("camera:\n  fov_deg: wide\n", "scene.yaml");
    const auto msg = error_of([&] { root.at("camera").get<double>("fov_deg"); });
    EXPECT_EQ(msg, "scene.yaml:2:12: camera.fov_deg: expected a number, found 'wide'");
}

TEST(Config, UnknownKeyIsReportedWithASuggestion) {
    const auto root = ConfigNode::parse("camra:\n  fov_deg: 30\n", "scene.yaml");
    const auto msg = error_of([&] { root.check_keys({"camera", "sky", "objects"}); });
    EXPECT_NE(msg.find("scene.yaml:1:1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("unknown key 'camra'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("did you mean 'camera'"), std::string::npos) << msg;
}

TEST(Config, MissingFieldNamesTheParent) {
    const auto root = ConfigNode::parse(kScene, "scene.yaml");
    const auto msg =
        error_of([&] { root.at("objects").elements()[0].get<std::string>("material"); });
    EXPECT_NE(msg.find("scene.yaml:7:5: objects[0]: missing required field 'material'"),
              std::string::npos)
        << msg;
}

TEST(Config, MalformedYamlGivesTheLine) {
    const auto msg =
        error_of([] { ConfigNode::parse("camera:\n  fov_deg: [30, 40\nsky: x\n", "bad.yaml"); });
    EXPECT_NE(msg.find("bad.yaml:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("YAML syntax error"), std::string::npos) << msg;
}

TEST(Config, OutOfRangeAndNonFiniteValues) {
    const auto root = ConfigNode::parse("a: 1.5\nb: .nan\nc: 3\n", "x.yaml");
    EXPECT_NE(
        error_of([&] { root.get_in_range("a", 0.0, 1.0); }).find("expected a number in [0, 1]"),
        std::string::npos);
    EXPECT_NE(error_of([&] { root.get<double>("b"); }).find("finite"), std::string::npos);
    EXPECT_NE(error_of([&] { root.get<bool>("c"); }).find("expected true or false, found '3'"),
              std::string::npos);
    EXPECT_NE(error_of([&] { root.get<int>("a"); }).find("expected an integer, found '1.5'"),
              std::string::npos);
}

TEST(Config, MissingFileAndRelativePaths) {
    test::TempDir dir;
    EXPECT_NE(error_of([&] { ConfigNode::load_file(dir / "none.yaml"); }).find("no such file"),
              std::string::npos);
    test::write_text(dir / "sub" / "s.yaml", "mesh: car.obj\n");
    const auto root = ConfigNode::load_file(dir / "sub" / "s.yaml");
    EXPECT_EQ(root.resolve_path(root.get<std::string>("mesh")), dir / "sub" / "car.obj");
}

TEST(Config, ClosestMatch) {
    EXPECT_EQ(closest_match("temprature_k", {"temperature_k", "material"}), "temperature_k");
    EXPECT_EQ(closest_match("zzzz", {"temperature_k", "material"}), "");
}

}  // namespace
}  // namespace tirpol
