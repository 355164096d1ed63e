// The pBRDF model registry: every file of materials/src/models/ is a model by its name, each name
// builds its own model, and a wrong name or a field the model does not take fails where it is.

#include "brdf_registry.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "lambertian.h"
#include "smooth_fresnel.h"
#include "test_support.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::materials {
namespace {

using ::testing::HasSubstr;

std::string error_of(const std::string& yaml) {
    try {
        brdf_from_config(ConfigNode::parse(yaml, "model.yaml"));
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(BrdfRegistry, EveryFileOfTheModelsFolderIsARegisteredModel) {
    std::vector<std::string> files;
    for (const auto& entry :
         std::filesystem::directory_iterator(test::source_dir() / "materials/src/models"))
        if (entry.path().extension() == ".cpp") files.push_back(entry.path().stem().string());
    std::sort(files.begin(), files.end());
    ASSERT_FALSE(files.empty());
    EXPECT_EQ(brdf_model_names(), files);
}

TEST(BrdfRegistry, EachNameBuildsItsOwnModel) {
    const auto fresnel = brdf_from_config(ConfigNode::parse(
        "model: smooth_fresnel\nrefractive_index: {n: 1.5, k: 0.01}\n", "fresnel.yaml"));
    EXPECT_NE(dynamic_cast<const SmoothFresnelBrdf*>(fresnel.get()), nullptr);
    const auto diffuse = brdf_from_config(
        ConfigNode::parse("model: lambertian\nparameters: {reflectance: 0.2}\n", "diffuse.yaml"));
    EXPECT_NE(dynamic_cast<const LambertianBrdf*>(diffuse.get()), nullptr);
    const auto facets = brdf_from_config(ConfigNode::parse(
        "model: microfacet\nrefractive_index: {n: 1.5, k: 0.01}\nparameters: {sigma: 0.3}\n",
        "facets.yaml"));
    EXPECT_NE(dynamic_cast<const MicrofacetBrdf*>(facets.get()), nullptr);
}

TEST(BrdfRegistry, UnknownModelFailsAtItsLineListingTheRegisteredModels) {
    const std::string message = error_of("name: x\nmodel: phong\n");
    EXPECT_THAT(message, HasSubstr("model.yaml:2"));
    EXPECT_THAT(message, HasSubstr("unknown model \"phong\""));
    EXPECT_THAT(message, HasSubstr("lambertian, microfacet, smooth_fresnel"));
}

TEST(BrdfRegistry, AModelRefusesTheFieldsItDoesNotTake) {
    EXPECT_THAT(error_of("model: smooth_fresnel\nrefractive_index: {n: 1.5, k: 0}\n"
                         "parameters: {sigma: 0.3}\n"),
                HasSubstr("no parameters besides refractive_index"));
    EXPECT_THAT(error_of("model: lambertian\nrefractive_index: {n: 1.5, k: 0}\n"
                         "parameters: {reflectance: 0.2}\n"),
                HasSubstr("no refractive index"));
    EXPECT_THAT(error_of("model: microfacet\nrefractive_index: {n: 1.5, k: 0}\n"),
                HasSubstr("missing field `parameters`"));
}

}  // namespace
}  // namespace tirpol::materials
