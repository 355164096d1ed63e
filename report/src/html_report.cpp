#include "html_report.h"

#include <fmt/format.h>

#include <cmath>
#include <functional>

#include "figures.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/utf8.h"
#include "tirpol/report/comparison_report.h"

namespace tirpol::report::detail {

namespace {

std::string num(double v) {
    if (!std::isfinite(v)) return "–";
    return fmt::format("{:.4g}", v);
}
std::string percent(double v) { return fmt::format("{:.2f} %", 100.0 * v); }

std::string degrees_of_freedom(double dof) {
    return std::isfinite(dof) ? fmt::format("{:g}", dof) : "∞";
}

constexpr const char* kStyle = R"css(
:root { --ink: #1d2330; --muted: #5b6475; --rule: #d5d9e0; --band: #f4f6f9; --ok: #1e7b34; --bad: #b3261e; --warn: #9a5b00; }
* { box-sizing: border-box; }
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; color: var(--ink);
       max-width: 1200px; margin: 0 auto; padding: 24px 28px 48px; line-height: 1.45; font-size: 15px; }
header { border-bottom: 3px solid var(--ink); margin-bottom: 18px; }
h1 { font-size: 26px; margin: 0 0 6px; }
h2 { font-size: 20px; margin: 30px 0 10px; padding-bottom: 4px; border-bottom: 1px solid var(--rule); }
h3 { font-size: 16px; margin: 18px 0 6px; }
.meta { color: var(--muted); margin: 0 0 12px; }
code { font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 13px; background: var(--band);
       padding: 1px 4px; border-radius: 3px; word-break: break-all; }
table { border-collapse: collapse; margin: 8px 0 14px; font-size: 14px; width: 100%; }
caption { text-align: left; font-weight: 600; padding: 4px 0; }
th, td { border-bottom: 1px solid var(--rule); padding: 4px 8px; text-align: right; vertical-align: top; }
th { background: var(--band); font-weight: 600; }
th:first-child, td:first-child { text-align: left; }
td.text, th.text { text-align: left; }
tbody tr:nth-child(even) { background: #fafbfc; }
.ok { color: var(--ok); font-weight: 600; }
.bad { color: var(--bad); font-weight: 600; }
.warn { color: var(--warn); font-weight: 600; }
.muted { color: var(--muted); }
.swatch { display: inline-block; width: 11px; height: 11px; border-radius: 2px; margin-right: 6px; vertical-align: -1px; }
figure { margin: 12px 0 20px; }
figure img { display: block; max-width: 100%; height: auto; border: 1px solid var(--rule); }
figcaption { color: var(--muted); font-size: 13.5px; margin-top: 5px; }
.grid { display: grid; grid-template-columns: repeat(auto-fit, minmax(360px, 1fr)); gap: 8px 18px; }
.notes li { margin-bottom: 4px; }
.summary td:first-child { width: 22%; }
p.answer { font-size: 16px; background: var(--band); border-left: 4px solid var(--ink); padding: 10px 14px; }
footer { margin-top: 36px; color: var(--muted); font-size: 13px; border-top: 1px solid var(--rule); padding-top: 8px; }
@media print {
  @page { size: A4; margin: 14mm; }
  body { max-width: none; padding: 0; font-size: 10pt; }
  h2 { break-after: avoid; }
  figure, table, tr { break-inside: avoid; }
  .grid { grid-template-columns: 1fr 1fr; }
  code { background: none; }
  tbody tr:nth-child(even) { background: none; }
}
)css";

}  // namespace

std::string escape_markup(std::string_view text) {
    std::string out;
    for (char c : valid_utf8(text)) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string base64_encode(std::string_view bytes) {
    static constexpr char kAlphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const auto v = (static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16) |
                       (static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8) |
                       static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 2]));
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += kAlphabet[v & 63];
    }
    if (const std::size_t rest = bytes.size() - i; rest > 0) {
        std::uint32_t v = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
        if (rest == 2)
            v |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

namespace {

// What every section reads.
struct Page {
    const CompareResult& r;
    const std::string& measured_name;
    const std::string& simulated_name;
    const std::vector<Figure>& figures;
    std::string units;  ///< HTML-escaped
};

std::string figures_of(const Page& p, const std::string& section, bool grid) {
    std::string h;
    if (grid) h += "<div class=\"grid\">\n";
    for (const auto& f : p.figures) {
        if (f.section != section) continue;
        if (!f.svg.empty())
            h += fmt::format("<figure>{}<figcaption>{}</figcaption></figure>\n", f.svg,
                             escape_markup(f.caption));
        else
            h += fmt::format(
                "<figure><img src=\"data:image/png;base64,{}\" "
                "alt=\"{}\"><figcaption>{}</figcaption></figure>\n",
                base64_encode(read_file(f.file)), escape_markup(f.file.filename().string()),
                escape_markup(f.caption));
    }
    if (grid) h += "</div>\n";
    return h;
}

std::string swatch(std::size_t index) {
    return fmt::format("<span class=\"swatch\" style=\"background:{}\"></span>",
                       region_colour_css(index));
}

const char* verdict_class(Agreement v) {
    switch (v) {
        case Agreement::ConsistentWithNoise:
            return "ok";
        case Agreement::ExceedsNoise:
            return "bad";
        case Agreement::NoData:
            break;
    }
    return "muted";
}

std::string verdict_span(Agreement v) {
    return fmt::format("<span class=\"{}\">{}</span>", verdict_class(v),
                       escape_markup(to_string(v)));
}

std::string sigma_span(SigmaCheck c) {
    const char* css = c == SigmaCheck::Plausible ? "ok"
                      : c == SigmaCheck::NoData  ? "muted"
                                                 : "warn";
    return fmt::format("<span class=\"{}\">{}</span>", css, escape_markup(to_string(c)));
}

std::string kelvin_text(const std::optional<KelvinBias>& k) {
    if (!k) return "–";
    return fmt::format("{} ± {} K", num(k->bias_k), num(k->bias_sigma_k));
}

std::string header_section(const Page& p) {
    const auto& r = p.r;
    return fmt::format(
        "<header>\n<h1>Measured vs simulated Stokes images</h1>\n<p class=\"meta\">Measured "
        "<code>{}</code> "
        "({}×{}) · simulated <code>{}</code> ({}×{}) · Stokes in {} · written by "
        "<code>{}</code></p>\n"
        "</header>\n",
        escape_markup(p.measured_name), r.width, r.height, escape_markup(p.simulated_name),
        r.simulated_width, r.simulated_height, p.units,
        escape_markup(r.provenance.tool_version.empty() ? "tirpol compare"
                                                        : r.provenance.tool_version));
}

std::string summary_section(const Page& p) {
    const auto& r = p.r;
    const auto& g = r.registration;
    std::string h = "<section id=\"summary\">\n<h2>Summary</h2>\n<p class=\"answer\">" +
                    escape_markup(summary_paragraph(r)) +
                    "</p>\n<table class=\"summary\">\n<tbody>\n";
    h += fmt::format("<tr><td>Registration</td><td class=\"text\">{} ({}): {}</td></tr>\n",
                     escape_markup(to_string(g.method)), escape_markup(g.model),
                     escape_markup(g.note));
    h += fmt::format(
        "<tr><td>Residual misalignment</td><td class=\"text\">{} px (dx = {}, dy = {} px; phase "
        "correlation of S0 gradients after registration)</td></tr>\n",
        num(std::hypot(g.residual_shift_px[0], g.residual_shift_px[1])),
        num(g.residual_shift_px[0]), num(g.residual_shift_px[1]));
    for (std::size_t i = 0; i < r.regions.size(); ++i) {
        const auto& region = r.regions[i];
        std::string per_quantity;
        for (const Quantity q : kZQuantities) {
            const auto& v = region.verdicts[q];
            const bool powerless =
                v.mean.verdict != Agreement::NoData && !verdict_has_power(region, q);
            per_quantity += fmt::format(
                "{}{}: {}{} — {}; {} ({})", per_quantity.empty() ? "" : "<br>", quantity_name(q),
                verdict_span(v.mean.verdict),
                powerless ? " <span class=\"warn\">(no power: detectable bias ≥ |simulated|)</span>"
                          : "",
                escape_markup(explain(v.mean)), sigma_span(v.sigma.verdict),
                escape_markup(explain(v.sigma)));
        }
        h += fmt::format(
            "<tr><td>{}{}</td><td class=\"text\"><strong>{}</strong><br>{}<br>S0 bias {} "
            "{}{}</td></tr>\n",
            swatch(i), escape_markup(region.name), verdict_span(region.verdict), per_quantity,
            num(region.stats.s0.bias), p.units,
            region.s0_bias_k ? " = " + kelvin_text(region.s0_bias_k) : std::string());
    }
    h += "</tbody>\n</table>\n";
    if (!r.notes.empty()) {
        h += "<ul class=\"notes\">\n";
        for (const auto& note : r.notes) h += "<li>" + escape_markup(note) + "</li>\n";
        h += "</ul>\n";
    }
    return h + "</section>\n";
}

std::string provenance_section(const Page& p) {
    const auto& pv = p.r.provenance;
    std::string h =
        "<section id=\"provenance\">\n<h2>Provenance</h2>\n<table class=\"summary\">\n<tbody>\n";
    h += fmt::format("<tr><td>Tool</td><td class=\"text\">{}</td></tr>\n",
                     pv.tool_version.empty() ? "tirpol report library (no CLI)"
                                             : escape_markup(pv.tool_version));
    h += fmt::format("<tr><td>Build commit</td><td class=\"text\"><code>{}</code></td></tr>\n",
                     escape_markup(pv.build_commit));
    if (!pv.command_line.empty())
        h += fmt::format("<tr><td>Command</td><td class=\"text\"><code>{}</code></td></tr>\n",
                         escape_markup(pv.command_line));
    if (p.r.band_um)
        h += fmt::format("<tr><td>Band</td><td class=\"text\">{}–{} µm (from {})</td></tr>\n",
                         num((*p.r.band_um)[0]), num((*p.r.band_um)[1]),
                         escape_markup(p.r.band_source));
    h += "</tbody>\n</table>\n";
    if (pv.inputs.empty())
        return h + "<p>No input files recorded (images passed in memory).</p>\n</section>\n";
    h += "<table>\n<caption>Input files (paths relative to this report's "
         "folder)</caption>\n<thead><tr><th class=\"text\">Role</th><th "
         "class=\"text\">File</th>"
         "<th>Bytes</th><th class=\"text\">SHA-256</th></tr></thead>\n<tbody>\n";
    for (const auto& f : pv.inputs)
        h += fmt::format(
            "<tr><td>{}</td><td class=\"text\"><code>{}</code></td><td>{}</td><td "
            "class=\"text\"><code>{}"
            "</code></td></tr>\n",
            escape_markup(f.role), escape_markup(f.path.string()), f.size_bytes, f.sha256);
    h += "</tbody>\n</table>\n";
    for (const auto& f : pv.inputs) {
        if (f.attributes.empty()) continue;
        h += fmt::format(
            "<table>\n<caption>Header of the {} file (scene, band, spp, seed, capture time, "
            "calibration "
            "files — as written by the tool that made it)</caption>\n<tbody>\n",
            escape_markup(f.role));
        for (const auto& [name, value] : f.attributes)
            h += fmt::format("<tr><td>{}</td><td class=\"text\"><code>{}</code></td></tr>\n",
                             escape_markup(name), escape_markup(value));
        h += "</tbody>\n</table>\n";
    }
    return h + "</section>\n";
}

std::string registration_section(const Page& p) {
    const auto& g = p.r.registration;
    std::string h =
        "<section "
        "id=\"registration\">\n<h2>Registration</h2>\n<table>\n<thead><tr><th>Quantity</th>"
        "<th>Value</th></tr></thead>\n<tbody>\n";
    h += fmt::format("<tr><td>Method / model</td><td>{} / {}</td></tr>\n",
                     escape_markup(to_string(g.method)), escape_markup(g.model));
    const auto& m = g.measured_to_simulated;
    h += fmt::format(
        "<tr><td>H (measured → simulated pixels)</td><td><code>[{} {} {}; {} {} {}; {} {} "
        "{}]</code></td></tr>\n",
        num(m[0]), num(m[1]), num(m[2]), num(m[3]), num(m[4]), num(m[5]), num(m[6]), num(m[7]),
        num(m[8]));
    h += fmt::format("<tr><td>Largest corner displacement [px]</td><td>{}</td></tr>\n",
                     num(g.max_corner_displacement_px));
    h += fmt::format("<tr><td>Rotation [°]</td><td>{}</td></tr>\n", num(g.rotation_deg));
    h += fmt::format("<tr><td>Control-point RMS residual [px]</td><td>{}</td></tr>\n",
                     g.control_point_rms_px ? num(*g.control_point_rms_px) : "–");
    h += fmt::format("<tr><td>ECC correlation coefficient</td><td>{}</td></tr>\n",
                     g.ecc_correlation ? num(*g.ecc_correlation) : "–");
    if (g.identity_edge_mismatch && g.registered_edge_mismatch)
        h +=
            fmt::format("<tr><td>S0 edge mismatch, identity / ECC warp</td><td>{} / {}</td></tr>\n",
                        num(*g.identity_edge_mismatch), num(*g.registered_edge_mismatch));
    h += fmt::format(
        "<tr><td>Residual shift after registration (dx, dy) [px]</td><td>{}, {}</td></tr>\n",
        num(g.residual_shift_px[0]), num(g.residual_shift_px[1]));
    return h + "</tbody>\n</table>\n</section>\n";
}

std::string regions_section(const Page& p) {
    return "<section id=\"regions\">\n<h2>Regions of interest</h2>\n" +
           figures_of(p, "regions", false) + "</section>\n";
}

std::string images_section(const Page& p) {
    return "<section id=\"images\">\n<h2>Stokes images side by side</h2>\n<p>Measured and "
           "registered simulated images "
           "share one colour scale per quantity; differences are measured − simulated.</p>\n" +
           figures_of(p, "images", false) + "</section>\n";
}

std::string statistics_section(const Page& p) {
    const auto& r = p.r;
    std::string h =
        "<section id=\"statistics\">\n<h2>Region statistics</h2>\n<p>Means and standard deviations "
        "over the "
        "pixels of each region where both images have data; bias = mean(m − s) ± its standard "
        "error "
        "(pixels treated as independent), RMSE = √mean((m − s)²).</p>\n";
    for (const Quantity q : kComparedQuantities) {
        const std::string qu = q == Quantity::DoLP ? "dimensionless" : p.units;
        h += fmt::format(
            "<table>\n<caption>{} [{}]</caption>\n<thead><tr><th>Region</th><th>Pixels</th>"
            "<th>Measured mean</th><th>Measured std</th><th>Simulated mean</th><th>Simulated "
            "std</th>"
            "<th>Bias</th><th>RMSE</th></tr></thead>\n<tbody>\n",
            quantity_name(q), qu);
        for (std::size_t i = 0; i < r.regions.size(); ++i) {
            const auto& s = r.regions[i].stats[q];
            h += fmt::format(
                "<tr><td>{}{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{} ± "
                "{}</td>"
                "<td>{}</td></tr>\n",
                swatch(i), escape_markup(r.regions[i].name), s.pixel_count, num(s.measured_mean),
                num(s.measured_std), num(s.simulated_mean), num(s.simulated_std), num(s.bias),
                num(s.bias_sigma), num(s.rmse));
        }
        h += "</tbody>\n</table>\n";
    }
    if (r.band_um) {
        h += fmt::format(
            "<table>\n<caption>S0 bias as a brightness-temperature difference ({}–{} µm band, box "
            "response)</caption>\n<thead><tr><th>Region</th><th>T_b of simulated S0 "
            "[K]</th><th>dL/dT "
            "[W/(m²·sr·K)]</th><th>S0 bias [K]</th></tr></thead>\n<tbody>\n",
            num((*r.band_um)[0]), num((*r.band_um)[1]));
        for (std::size_t i = 0; i < r.regions.size(); ++i) {
            const auto& k = r.regions[i].s0_bias_k;
            h += fmt::format("<tr><td>{}{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n", swatch(i),
                             escape_markup(r.regions[i].name), k ? num(k->temperature_k) : "–",
                             k ? num(k->radiance_dT) : "–", kelvin_text(k));
        }
        h += "</tbody>\n</table>\n";
    }
    if (!r.background.empty()) {
        h += fmt::format(
            "<table>\n<caption>S1 contrast against the background region “{}” "
            "[{}]</caption>\n<thead><tr>"
            "<th>Region</th><th>Measured</th><th>Simulated</th><th>Measured − "
            "simulated</th></tr></thead>\n"
            "<tbody>\n",
            escape_markup(r.background), p.units);
        for (std::size_t i = 0; i < r.regions.size(); ++i) {
            const auto& region = r.regions[i];
            if (region.name == r.background || !region.s1_contrast_measured) continue;
            h += fmt::format("<tr><td>{}{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n", swatch(i),
                             escape_markup(region.name), num(*region.s1_contrast_measured),
                             num(*region.s1_contrast_simulated),
                             num(*region.s1_contrast_measured - *region.s1_contrast_simulated));
        }
        h += "</tbody>\n</table>\n";
    }
    return h + "</section>\n";
}

std::string aop_section(const Page& p) {
    const auto& r = p.r;
    std::string h = fmt::format(
        "<section id=\"aop\">\n<h2>Angle of polarization</h2>\n<p>AoP is an axial angle (θ and θ + "
        "180° are the "
        "same): means and spreads are taken on 2θ (Mardia &amp; Jupp, <i>Directional "
        "Statistics</i>, §9.3.2), over the "
        "pixels where √(S1² + S2²) exceeds {:.0f} σ of its noise in <em>both</em> images — "
        "elsewhere AoP is the angle "
        "of noise.</p>\n<table>\n<thead><tr><th>Region</th><th>Polarized pixels</th><th>Measured "
        "mean [°]</th>"
        "<th>Simulated mean [°]</th><th>Mean difference [°]</th><th>Circular std of difference "
        "[°]</th></tr></thead>\n"
        "<tbody>\n",
        kAopSignificanceSigma);
    for (std::size_t i = 0; i < r.regions.size(); ++i) {
        const auto& a = r.regions[i].aop;
        const bool any = a.pixel_count > 0;
        h += fmt::format(
            "<tr><td>{}{}</td><td>{} of {}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
            swatch(i), escape_markup(r.regions[i].name), a.pixel_count, a.region_pixel_count,
            any ? num(a.measured_mean_deg) : "–", any ? num(a.simulated_mean_deg) : "–",
            any ? num(a.difference_mean_deg) : "–", any ? num(a.difference_std_deg) : "–");
    }
    return h + "</tbody>\n</table>\n</section>\n";
}

std::string noise_section(const Page& p) {
    const auto& r = p.r;
    std::string h = fmt::format(
        "<section id=\"noise\">\n<h2>Do the differences exceed the "
        "noise?</h2>\n<p><strong>Agreement</strong> (the "
        "verdict): per region and quantity, the mean difference d = mean(m − s) is tested against "
        "the standard "
        "uncertainty of that mean, σ_mean² = Σσ_m²/n² + Σσ_s²/n² + σ_common² + σ_registration² — "
        "the measured and "
        "simulated per-pixel noise is independent from pixel to pixel and averages down, the "
        "calibration's gain and "
        "offset errors and the misalignment are common to the region and do not. Its degrees of "
        "freedom ν follow "
        "Welch–Satterthwaite; <span class=\"bad\">exceeds noise</span> when |d|/σ_mean &gt; "
        "t<sub>1−α/2, ν</sub>, with "
        "α = {:.2f} % per quantity ({:.0f} % per region over S0, S1, S2, Šidák); otherwise <span "
        "class=\"ok\">"
        "consistent with noise</span>. The detectable bias (t<sub>1−α/2, ν</sub> + t<sub>{:.2f}, "
        "ν</sub>)·σ_mean is "
        "the smallest real difference found with {:.0f} % probability. <strong>σ "
        "diagnostic</strong> (separate): the "
        "per-pixel z = (m − s)/√(σ_m² + σ_s²), mapped from Student's t to the normal when a "
        "variance is estimated, "
        "has variance 1 about its mean when σ is right; a variance more than 3 of its sampling σ "
        "√(2/(n − 1)) away "
        "from 1, with a σ factor beyond {:.2f}, reads <span class=\"warn\">σ overestimated</span> "
        "or <span "
        "class=\"warn\">σ underestimated</span>.</p>\n",
        100.0 * r.design.false_alarm_per_quantity(), 100.0 * r.design.false_alarm_per_region,
        r.design.power, 100.0 * r.design.power, kSigmaFactorTolerance);
    h += fmt::format(
        "<table>\n<caption>Region-mean tests "
        "[{}]</caption>\n<thead><tr><th>Region</th><th>Quantity</th>"
        "<th>Pixels</th><th>Mean difference</th><th>σ_mean</th><th>of which measured / common / "
        "simulated "
        "/ registration</th><th>ν</th><th>t</th><th>p</th><th>Detectable bias</th><th "
        "class=\"text\">"
        "Verdict</th><th class=\"text\">σ diagnostic</th></tr></thead>\n<tbody>\n",
        p.units);
    for (std::size_t i = 0; i < r.regions.size(); ++i)
        for (const Quantity q : kZQuantities) {
            const auto& v = r.regions[i].verdicts[q];
            const auto& t = v.mean;
            h += fmt::format(
                "<tr><td>{}{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{} / {} / {} / "
                "{}</td>"
                "<td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"text\">{}</td><td "
                "class=\"text\">"
                "{} (z variance {})</td></tr>\n",
                swatch(i), escape_markup(r.regions[i].name), quantity_name(q), t.pixel_count,
                num(t.difference), num(t.combined.sigma), num(t.measured_independent.sigma),
                num(t.measured_common.sigma), num(t.simulated.sigma), num(t.registration.sigma),
                degrees_of_freedom(t.combined.dof), num(t.t), num(t.p_value),
                num(t.detectable_bias), verdict_span(t.verdict), sigma_span(v.sigma.verdict),
                num(v.sigma.z_variance));
        }
    h += "</tbody>\n</table>\n";
    h += fmt::format(
        "<table>\n<caption>Noise used [{}]; degrees of freedom ν of each variance (∞: taken as "
        "exact)"
        "</caption>\n<thead><tr><th>Quantity</th><th class=\"text\">Measured σ from</th><th>Median "
        "σ_m</th>"
        "<th>ν_m</th><th class=\"text\">Simulated σ from</th><th>Median "
        "σ_s</th><th>ν_s</th></tr></thead>\n"
        "<tbody>\n",
        p.units);
    for (const Quantity q : kZQuantities) {
        const NoiseSource& s = r.noise[q];
        h += fmt::format(
            "<tr><td>{}</td><td class=\"text\">{}</td><td>{}</td><td>{}</td><td "
            "class=\"text\">{}</td>"
            "<td>{}</td><td>{}</td></tr>\n",
            quantity_name(q), escape_markup(s.measured), num(s.measured_sigma_median),
            degrees_of_freedom(s.measured_dof), escape_markup(s.simulated),
            num(s.simulated_sigma_median), degrees_of_freedom(s.simulated_dof));
    }
    h += "</tbody>\n</table>\n";
    h += "<table>\n<caption>Fraction of pixels beyond 2σ and "
         "3σ</caption>\n<thead><tr><th>Region</th><th>Quantity</th>"
         "<th>Pixels</th><th>|z| &gt; 2</th><th>|z| &gt; 3</th><th>Mean z</th><th>RMS z</th><th "
         "class=\"text\">σ diagnostic</th>"
         "</tr></thead>\n<tbody>\n";
    for (std::size_t i = 0; i < r.regions.size(); ++i)
        for (std::size_t k = 0; k <= kZQuantities.size(); ++k) {
            const bool pooled = k == kZQuantities.size();  // the last row: S0, S1, S2 pooled
            const auto& z = pooled ? r.regions[i].z_pooled : r.regions[i].z[kZQuantities[k]];
            h += fmt::format(
                "<tr><td>{}{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</"
                "td>"
                "<td class=\"text\">{}</td></tr>\n",
                swatch(i), escape_markup(r.regions[i].name),
                pooled ? "S0+S1+S2 pooled" : quantity_name(kZQuantities[k]), z.pixel_count,
                percent(z.fraction_above_2), percent(z.fraction_above_3), num(z.mean), num(z.rms),
                pooled ? "(reference only)"
                       : sigma_span(r.regions[i].verdicts[kZQuantities[k]].sigma.verdict));
        }
    h += fmt::format(
        "<tr><td>expected (noise "
        "only)</td><td></td><td></td><td>{}</td><td>{}</td><td>0</td><td>1</td>"
        "<td></td></tr>\n</tbody>\n</table>\n",
        percent(kNormalTailAbove2), percent(kNormalTailAbove3));
    return h + figures_of(p, "z", false) + "</section>\n";
}

std::string scatter_section(const Page& p) {
    return "<section id=\"scatter\">\n<h2>Scatter plots</h2>\n" + figures_of(p, "scatter", true) +
           "</section>\n";
}

std::string histograms_section(const Page& p) {
    return "<section id=\"histograms\">\n<h2>Histograms of the differences</h2>\n" +
           figures_of(p, "histograms", true) + "</section>\n";
}

std::string footer_section(const Page&) {
    return "<footer>Files next to this page: <code>report.json</code> (every number above), "
           "<code>comparison.exr</code> "
           "(full-resolution measured, registered simulated, difference and z planes) and the PNG "
           "figures. Stokes "
           "convention: S1 = I0 − I90, S2 = I45 − I135 in the camera frame (polarizer 0° along "
           "image rows); DoLP and "
           "AoP are recomputed from S0, S1, S2 after registration.</footer>\n";
}

// The page, top to bottom: a new section is one function and one entry here.
const std::vector<std::function<std::string(const Page&)>> kSections = {
    header_section,  summary_section, provenance_section, registration_section,
    regions_section, images_section,  statistics_section, aop_section,
    noise_section,   scatter_section, histograms_section, footer_section};

}  // namespace

std::string render_html(const CompareResult& r, const std::string& measured_name,
                        const std::string& simulated_name, const std::vector<Figure>& figures) {
    const Page page{r, measured_name, simulated_name, figures, escape_markup(r.units)};
    std::string h =
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
    h += fmt::format("<title>tirpol comparison: {} vs {}</title>\n", escape_markup(measured_name),
                     escape_markup(simulated_name));
    h += fmt::format("<style>{}</style>\n</head>\n<body>\n", kStyle);
    for (const auto& section : kSections) h += section(page);
    return h + "</body>\n</html>\n";
}

}  // namespace tirpol::report::detail
