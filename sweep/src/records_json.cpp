#include "records_json.h"

#include <cmath>
#include <limits>

#include "tirpol/core/error.h"

namespace tirpol::sweep::detail {

namespace {

// JSON has no NaN: an undefined mean or error (empty region, one sample per pixel) is null.
nlohmann::json number(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}
double number_from(const nlohmann::json& j) {
    return j.is_null() ? std::numeric_limits<double>::quiet_NaN() : j.get<double>();
}

nlohmann::json values_json(const QuantityEstimates& q) {
    nlohmann::json j = nlohmann::json::object();
    for (std::size_t i = 0; i < std::size(kQuantityNames); ++i)
        j[kQuantityNames[i]] = {{"mean", number(quantity(q, i).mean)},
                                {"error", number(quantity(q, i).error)}};
    return j;
}

QuantityEstimates values_from(const nlohmann::json& j) {
    QuantityEstimates q;
    Estimate* all[] = {&q.s0, &q.s1, &q.s2, &q.dolp, &q.temperature_k};
    for (std::size_t i = 0; i < std::size(kQuantityNames); ++i) {
        const auto& e = j.at(kQuantityNames[i]);
        *all[i] = {number_from(e.at("mean")), number_from(e.at("error"))};
    }
    return q;
}

}  // namespace

nlohmann::json statistics_json(const PointStatistics& s) {
    nlohmann::json regions = nlohmann::json::array(), contrasts = nlohmann::json::array();
    for (const auto& r : s.regions)
        regions.push_back(
            {{"name", r.name}, {"pixel_count", r.pixel_count}, {"values", values_json(r.values)}});
    for (const auto& c : s.contrasts)
        contrasts.push_back({{"name", c.name}, {"values", values_json(c.values)}});
    return {{"regions", regions}, {"contrasts", contrasts}};
}

PointStatistics statistics_from_json(const nlohmann::json& j, const std::string& source) {
    try {
        PointStatistics s;
        for (const auto& r : j.at("regions"))
            s.regions.push_back({r.at("name").get<std::string>(),
                                 r.at("pixel_count").get<std::size_t>(),
                                 values_from(r.at("values"))});
        for (const auto& c : j.at("contrasts"))
            s.contrasts.push_back({c.at("name").get<std::string>(), values_from(c.at("values"))});
        return s;
    } catch (const nlohmann::json::exception& e) {
        fail("{}: malformed point statistics: {}", source, e.what());
    }
}

nlohmann::json parameters_json(const SweepSpec& spec, const SweepPoint& point) {
    nlohmann::json j = nlohmann::json::object();
    for (std::size_t a = 0; a < spec.axes.size(); ++a)
        j[spec.axes[a].parameter] = spec.axes[a].labels[point.value_index[a]];
    return j;
}

nlohmann::json record_json(const SweepSpec& spec, const PointRecord& r) {
    nlohmann::json j = {{"index", r.point.index},
                        {"id", r.point.id},
                        {"parameters", parameters_json(spec, r.point)},
                        {"seed", r.point.seed},
                        {"status", r.status},
                        {"error", r.error},
                        {"rank", r.rank},
                        {"seconds", r.seconds},
                        {"wait_seconds", r.wait_seconds}};
    j["render_seconds"] = r.render_seconds;
    j["statistics"] = r.statistics ? statistics_json(*r.statistics) : nlohmann::json(nullptr);
    return j;
}

PointRecord record_from_json(const nlohmann::json& j, const std::vector<SweepPoint>& points) {
    const auto index = j.at("index").get<std::size_t>();
    if (index >= points.size())
        fail("point record with index {} of a sweep of {} points", index, points.size());
    PointRecord r{points[index],
                  j.at("status").get<std::string>(),
                  j.at("error").get<std::string>(),
                  j.at("rank").get<int>(),
                  j.at("seconds").get<double>(),
                  j.at("render_seconds").get<double>(),
                  j.at("wait_seconds").get<double>(),
                  std::nullopt};
    if (!j.at("statistics").is_null())
        r.statistics = statistics_from_json(j.at("statistics"), "point " + r.point.id);
    return r;
}

}  // namespace tirpol::sweep::detail
