// ConfigNode::with_value: the override a sweep point applies to its base scene, read by the one
// loader.

#include <gtest/gtest.h>

#include "tirpol/core/config.h"
#include "tirpol/core/error.h"

namespace tirpol {
namespace {

constexpr const char* kScene = R"(camera:
  fov_deg: 30
  position: [0, -3, 1]
objects:
  - name: snow
    temperature: -3
  - name: ball
    temperature: 18
)";

std::string error_of(const ConfigNode& root, const std::string& path, const ConfigNode& value) {
    try {
        root.with_value(path, value);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(ConfigWithValue, ReplacesTheNamedNodeAndLeavesTheBaseUntouched) {
    const ConfigNode base = ConfigNode::parse(kScene, "scene.yaml");
    const ConfigNode value = ConfigNode::parse("[1, 2, 3]", "sweep.yaml");
    const ConfigNode changed = base.with_value("camera.position", value);
    EXPECT_EQ(changed.at("camera").get<std::vector<double>>("position"),
              (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(base.at("camera").get<std::vector<double>>("position"),
              (std::vector<double>{0, -3, 1}));
    EXPECT_EQ(changed.at("camera").get<double>("fov_deg"), 30.0);
    EXPECT_EQ(changed.file(), base.file());
}

TEST(ConfigWithValue, SelectsListElementsByNameOrIndex) {
    const ConfigNode base = ConfigNode::parse(kScene, "scene.yaml");
    const ConfigNode by_name =
        base.with_value("objects[ball].temperature", ConfigNode::parse("25"));
    const ConfigNode by_index = base.with_value("objects[0].temperature", ConfigNode::parse("-8"));
    EXPECT_EQ(by_name.at("objects").elements()[1].get<double>("temperature"), 25.0);
    EXPECT_EQ(by_name.at("objects").elements()[0].get<double>("temperature"), -3.0);
    EXPECT_EQ(by_index.at("objects").elements()[0].get<double>("temperature"), -8.0);
}

TEST(ConfigWithValue, UntouchedNodesKeepTheirLinesForErrors) {
    const ConfigNode base = ConfigNode::parse(kScene, "scene.yaml");
    const ConfigNode changed =
        base.with_value("camera.fov_deg", ConfigNode::parse("40", "sweep.yaml"));
    // objects[1].temperature is on line 8 of the base file, column 18.
    EXPECT_EQ(changed.at("objects").elements()[1].at("temperature").location(), "scene.yaml:8:18");
}

TEST(ConfigWithValue, UnknownStepsAreNamedWithASuggestion) {
    const ConfigNode base = ConfigNode::parse(kScene, "scene.yaml");
    const ConfigNode v = ConfigNode::parse("1");
    EXPECT_NE(
        error_of(base, "camera.positon", v).find("no field 'positon' — did you mean 'position'?"),
        std::string::npos)
        << error_of(base, "camera.positon", v);
    EXPECT_NE(error_of(base, "objects[bal].temperature", v).find("did you mean 'ball'?"),
              std::string::npos);
    EXPECT_NE(error_of(base, "objects[5].temperature", v).find("no element '5'"),
              std::string::npos);
    EXPECT_NE(error_of(base, "camera.fov_deg.x", v).find("'x' is a field"), std::string::npos);
    EXPECT_NE(error_of(base, "camera..fov_deg", v).find("empty step"), std::string::npos);
    EXPECT_NE(error_of(base, "camera[0]", v).find("selects a list element"), std::string::npos);
}

}  // namespace
}  // namespace tirpol
