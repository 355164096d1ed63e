// `tirpol fit-render` as one library call (fitting::run_render_fit): the text of --free and --view
// is checked before any file is read, and text of the wrong form is an OptionValueError naming the
// option (the CLI exits 2 with it). Fits themselves are tested in render_fit_test.cpp.

#include <gtest/gtest.h>

#include "tirpol/core/limits.h"
#include "tirpol/fitting/render_fit.h"

namespace tirpol::fitting {
namespace {

// The option an OptionValueError of run_render_fit names and its message; option "" for another
// error.
std::pair<std::string, std::string> refusal(const RenderFitRunOptions& options) {
    try {
        run_render_fit(options);
    } catch (const OptionValueError& e) {
        return {e.option(), e.what()};
    } catch (const Error& e) {
        return {"", e.what()};
    }
    return {"", "no error"};
}

RenderFitRunOptions valid_text() {
    RenderFitRunOptions o;
    o.scene = "no-such-scene.yaml";  // never read while the text is wrong
    o.views = {"measured.exr", "measured.exr,camera.yaml,pose.yaml"};
    o.objects = {"panel"};
    o.free = {"paint.sigma=0.05:1", "paint.n=1.2:3:1.5"};
    return o;
}

TEST(FitRenderRun, BadFreeParameterTextNamesFreeBeforeAnyFileIsRead) {
    for (const std::string text : {"paint.sigma=0.05", "sigma=0.05:1", "paint.sigma=a:1",
                                   "paint.sigma=0.05:nan", "paint.sigma=1:2:3:4"}) {
        RenderFitRunOptions o = valid_text();
        o.free.push_back(text);
        const auto [option, message] = refusal(o);
        EXPECT_EQ(option, "--free") << text << ": " << message;
        EXPECT_NE(message.find(text), std::string::npos) << message;
    }
}

TEST(FitRenderRun, ViewTextNeedsOneOrThreePathsBeforeAnyFileIsRead) {
    for (const std::string text : {"measured.exr,camera.yaml", "a.exr,b.yaml,c.yaml,d.yaml"}) {
        RenderFitRunOptions o = valid_text();
        o.views.push_back(text);
        const auto [option, message] = refusal(o);
        EXPECT_EQ(option, "--view") << text << ": " << message;
        EXPECT_NE(message.find("MEASURED.exr,CAMERA.yaml,POSE.yaml"), std::string::npos) << message;
    }
    // Valid text: the first file read is the scene, which is missing (an input error, not usage).
    const auto [option, message] = refusal(valid_text());
    EXPECT_EQ(option, "");
    EXPECT_NE(message.find("no-such-scene.yaml"), std::string::npos) << message;
}

}  // namespace
}  // namespace tirpol::fitting
