#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/fitting/render_fit.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::fitting {

namespace {
// "MEASURED.exr" or "MEASURED.exr,CAMERA.yaml,POSE.yaml": the paths, three with empty camera and
// pose for the first form.
std::vector<std::string> view_paths(const std::string& spec) {
    std::vector<std::string> parts;
    for (std::size_t from = 0;;) {
        const auto comma = spec.find(',', from);
        parts.push_back(spec.substr(from, comma == std::string::npos ? comma : comma - from));
        if (comma == std::string::npos) break;
        from = comma + 1;
    }
    if (parts.size() != 1 && parts.size() != 3)
        throw OptionValueError(
            "--view", spec + ": expected MEASURED.exr or MEASURED.exr,CAMERA.yaml,POSE.yaml");
    parts.resize(3);
    return parts;
}
}  // namespace

RenderFitSummary run_render_fit(const RenderFitRunOptions& o) {
    RenderFitOptions fit = o.fit;
    for (const std::string& text : o.free) {
        try {
            fit.parameters.push_back(parse_render_fit_parameter(text));
        } catch (const Error& e) {
            throw OptionValueError("--free", e.what());
        }
    }
    std::vector<std::vector<std::string>> view_files;
    for (const std::string& spec : o.views) view_files.push_back(view_paths(spec));
    const simulation::Scene scene = simulation::load_scene(o.scene);
    std::vector<RenderFitView> views;
    for (const auto& files : view_files)
        views.push_back(load_render_fit_view(scene, files[0], files[1], files[2], o.objects));
    return fit_through_renderer(scene, views, fit);
}

}  // namespace tirpol::fitting
