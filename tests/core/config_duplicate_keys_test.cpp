// A key given twice in one YAML mapping is an error naming both places (before: yaml-cpp kept the
// first silently, against the documented strictness of tirpol's configs).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tirpol/core/config.h"
#include "tirpol/core/error.h"

namespace tirpol {
namespace {

std::string error_of(const std::string& yaml) {
    try {
        ConfigNode::parse(yaml, "plan.yaml");
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(ConfigDuplicateKeys, TopLevelDuplicateNamesBothLines) {
    EXPECT_EQ(error_of("settle_s: 0.5\nframes_per_angle: 4\nsettle_s: 2\n"),
              "plan.yaml:3:1: duplicate key 'settle_s' (first given at plan.yaml:1:1); each key "
              "may appear once in a "
              "mapping");
}

TEST(ConfigDuplicateKeys, NestedAndFlowMappingsAreChecked) {
    EXPECT_THAT(
        error_of("objects:\n  - name: a\n    material: x\n    name: b\n"),
        testing::HasSubstr("plan.yaml:4:5: duplicate key 'name' (first given at plan.yaml:2:5)"));
    EXPECT_THAT(error_of("site: {lat: 1, lat: 2}\n"), testing::HasSubstr("duplicate key 'lat'"));
}

TEST(ConfigDuplicateKeys, SameKeyInDifferentMappingsAndAliasesAreFine) {
    EXPECT_EQ(error_of("a: {x: 1}\nb: {x: 2}\nlist: [{x: 1}, {x: 2}]\n"), "(no error)");
    EXPECT_EQ(error_of("base: &b {x: 1, y: 2}\nc: *b\nd: *b\n"), "(no error)");
    // The values stay reachable as before.
    EXPECT_EQ(ConfigNode::parse("a: {x: 1}\nb: {x: 2}\n").at("b").get<int>("x"), 2);
}

TEST(ConfigDuplicateKeys, AliasExpansionStaysCheap) {
    // Nine levels of nine aliases: 9^9 paths, one node per level; the check visits each node once.
    std::string yaml = "l0: &l0 [x, x, x, x, x, x, x, x, x]\n";
    for (int i = 1; i < 9; ++i) {
        yaml += "l" + std::to_string(i) + ": &l" + std::to_string(i) + " [";
        for (int k = 0; k < 9; ++k) yaml += (k ? ", *l" : "*l") + std::to_string(i - 1);
        yaml += "]\n";
    }
    EXPECT_EQ(error_of(yaml), "(no error)");
}

}  // namespace
}  // namespace tirpol
