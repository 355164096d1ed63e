// NREL SPA, written from Reda & Andreas, NREL/TP-560-34302, section 3 (steps 3.1–3.15).

#include "tirpol/thermal/solar_position.h"

#include <algorithm>
#include <cmath>

#include "spa_periodic_terms.h"
#include "tirpol/core/error.h"
#include "tirpol/thermal/civil_time.h"

namespace tirpol::thermal {

namespace {

double limit_degrees(double deg) {
    const double limited = deg - 360.0 * std::floor(deg / 360.0);
    return limited < 0.0 ? limited + 360.0 : limited;
}

double sin_deg(double d) { return std::sin(deg_to_rad(d)); }
double cos_deg(double d) { return std::cos(deg_to_rad(d)); }

// Eqs. 9–12: Σ_i (Σ_j A cos(B + C·JME)) · JME^i / 1e8, in radians (L, B) or AU (R).
template <std::size_t N>
double periodic_sum(const std::array<std::span<const spa_tables::Term>, N>& series, double jme) {
    double total = 0.0;
    double power = 1.0;
    for (const auto& terms : series) {
        double s = 0.0;
        for (const auto& t : terms) s += t.a * std::cos(t.b + t.c * jme);
        total += s * power;
        power *= jme;
    }
    return total / 1e8;
}

double polynomial(double x, double a, double b, double c, double d) {
    return ((d * x + c) * x + b) * x + a;
}

}  // namespace

SolarPosition solar_position(const SpaInput& in) {
    if (!(std::abs(in.latitude_deg) <= 90.0))
        fail("SPA: latitude {}° outside −90…90°", in.latitude_deg);
    if (!(std::abs(in.longitude_deg) <= 180.0))
        fail("SPA: longitude {}° outside −180…180°", in.longitude_deg);
    // The input ranges of NREL's SPA (Reda & Andreas 2008, Table 1 / spa.c validate_inputs); NaN
    // fails each.
    if (!std::isfinite(in.unix_seconds))
        fail("SPA: time {} is not a finite number of seconds", in.unix_seconds);
    if (!(in.elevation_m >= -6500000.0 && std::isfinite(in.elevation_m)))
        fail("SPA: elevation {} m outside −6 500 000 m…+∞ (finite)", in.elevation_m);
    if (!(in.pressure_mbar >= 0.0 && in.pressure_mbar <= 5000.0))
        fail("SPA: pressure {} mbar outside 0…5000 mbar", in.pressure_mbar);
    if (!(in.temperature_c >= -273.0 && in.temperature_c <= 6000.0))
        fail("SPA: temperature {} °C outside −273…6000 °C", in.temperature_c);
    if (!(std::abs(in.delta_t_s) <= 8000.0))
        fail("SPA: ΔT {} s outside −8000…8000 s", in.delta_t_s);
    if (!(std::abs(in.delta_ut1_s) <= 1.0)) fail("SPA: ΔUT1 {} s outside −1…1 s", in.delta_ut1_s);
    SolarPosition out;

    // 3.1 Julian and Julian Ephemeris Day, century, millennium (eqs. 4–8). UT1 = UTC + ΔUT1.
    const double jd = julian_day(in.unix_seconds + in.delta_ut1_s);
    const double year = 2000.0 + (jd - 2451545.0) / 365.25;
    if (!(year >= -2000.0 && year <= 6000.0))
        fail("SPA: year {:.0f} outside the algorithm's −2000…6000", year);
    const double jde = jd + in.delta_t_s / 86400.0;
    const double jc = (jd - 2451545.0) / 36525.0;
    const double jce = (jde - 2451545.0) / 36525.0;
    const double jme = jce / 10.0;
    out.julian_day = jd;

    // 3.2 Earth heliocentric longitude, latitude, radius vector (eqs. 9–12).
    const double l_deg = limit_degrees(rad_to_deg(periodic_sum(spa_tables::kL, jme)));
    const double b_deg = rad_to_deg(periodic_sum(spa_tables::kB, jme));
    const double r_au = periodic_sum(spa_tables::kR, jme);
    out.heliocentric_longitude_deg = l_deg;
    out.heliocentric_latitude_deg = b_deg;
    out.earth_radius_au = r_au;

    // 3.3 Geocentric longitude and latitude (eqs. 13–14).
    const double theta = limit_degrees(l_deg + 180.0);
    const double beta = -b_deg;

    // 3.4 Nutation in longitude and obliquity (eqs. 15–23).
    const double x[5] = {
        polynomial(jce, 297.85036, 445267.111480, -0.0019142,
                   1.0 / 189474.0),  // mean elongation Moon–Sun
        polynomial(jce, 357.52772, 35999.050340, -0.0001603, -1.0 / 300000.0),  // mean anomaly Sun
        polynomial(jce, 134.96298, 477198.867398, 0.0086972, 1.0 / 56250.0),    // mean anomaly Moon
        polynomial(jce, 93.27191, 483202.017538, -0.0036825,
                   1.0 / 327270.0),  // Moon argument of latitude
        polynomial(jce, 125.04452, -1934.136261, 0.0020708, 1.0 / 450000.0),  // Moon ascending node
    };
    double dpsi = 0.0, deps = 0.0;
    for (const auto& t : spa_tables::kNutation) {
        double arg = 0.0;
        for (int i = 0; i < 5; ++i) arg += x[i] * t.y[i];
        arg = deg_to_rad(arg);
        dpsi += (t.a + t.b * jce) * std::sin(arg);
        deps += (t.c + t.d * jce) * std::cos(arg);
    }
    dpsi /= 36000000.0;
    deps /= 36000000.0;
    out.nutation_longitude_deg = dpsi;
    out.nutation_obliquity_deg = deps;

    // 3.5 True obliquity of the ecliptic (eqs. 24–25); U = JME/10, ε0 in arc seconds.
    const double u = jme / 10.0;
    static constexpr double kObliquity[] = {84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67,
                                            -39.05,    7.12,     27.87, 5.79,    2.45};
    double eps0 = 0.0;
    for (int i = 10; i >= 0; --i) eps0 = eps0 * u + kObliquity[i];
    const double eps = eps0 / 3600.0 + deps;
    out.true_obliquity_deg = eps;

    // 3.6–3.7 Aberration correction and apparent sun longitude (eqs. 26–27).
    const double dtau = -20.4898 / (3600.0 * r_au);
    const double lambda = theta + dpsi + dtau;

    // 3.8 Apparent sidereal time at Greenwich (eqs. 28–29).
    const double nu0 = limit_degrees(280.46061837 + 360.98564736629 * (jd - 2451545.0) +
                                     0.000387933 * jc * jc - jc * jc * jc / 38710000.0);
    const double nu = nu0 + dpsi * cos_deg(eps);

    // 3.9–3.10 Geocentric right ascension and declination (eqs. 30–31).
    const double alpha = limit_degrees(rad_to_deg(
        std::atan2(sin_deg(lambda) * cos_deg(eps) - std::tan(deg_to_rad(beta)) * sin_deg(eps),
                   cos_deg(lambda))));
    const double delta = rad_to_deg(
        std::asin(sin_deg(beta) * cos_deg(eps) + cos_deg(beta) * sin_deg(eps) * sin_deg(lambda)));
    out.right_ascension_deg = alpha;
    out.declination_deg = delta;

    // 3.11 Observer local hour angle (eq. 32).
    const double h = limit_degrees(nu + in.longitude_deg - alpha);
    out.hour_angle_deg = h;

    // 3.12 Topocentric right ascension and declination (eqs. 33–39): parallax for the observer's
    // position on the reference ellipsoid (flattening 0.99664719).
    const double xi = 8.794 / (3600.0 * r_au);
    const double u_rad = std::atan(0.99664719 * std::tan(deg_to_rad(in.latitude_deg)));
    const double xx = std::cos(u_rad) + in.elevation_m / 6378140.0 * cos_deg(in.latitude_deg);
    const double yy =
        0.99664719 * std::sin(u_rad) + in.elevation_m / 6378140.0 * sin_deg(in.latitude_deg);
    const double dalpha_rad =
        std::atan2(-xx * sin_deg(xi) * sin_deg(h), cos_deg(delta) - xx * sin_deg(xi) * cos_deg(h));
    const double dalpha = rad_to_deg(dalpha_rad);
    const double delta_p =
        rad_to_deg(std::atan2((sin_deg(delta) - yy * sin_deg(xi)) * std::cos(dalpha_rad),
                              cos_deg(delta) - xx * sin_deg(xi) * cos_deg(h)));
    out.topocentric_declination_deg = delta_p;

    // 3.13 Topocentric local hour angle (eq. 40).
    const double h_p = h - dalpha;

    // 3.14 Topocentric zenith angle (eqs. 41–44). Refraction only while the sun is above the
    // horizon.
    const double e0 =
        rad_to_deg(std::asin(sin_deg(in.latitude_deg) * sin_deg(delta_p) +
                             cos_deg(in.latitude_deg) * cos_deg(delta_p) * cos_deg(h_p)));
    double de = 0.0;
    if (e0 >= -(0.26667 + in.atmospheric_refraction_deg)) {
        de = in.pressure_mbar / 1010.0 * 283.0 / (273.0 + in.temperature_c) * 1.02 /
             (60.0 * std::tan(deg_to_rad(e0 + 10.3 / (e0 + 5.11))));
    }
    const double e = e0 + de;
    out.elevation_deg = e;
    out.zenith_deg = 90.0 - e;

    // 3.15 Topocentric azimuth (eqs. 45–46), from north, eastward.
    const double gamma = limit_degrees(rad_to_deg(
        std::atan2(sin_deg(h_p), cos_deg(h_p) * sin_deg(in.latitude_deg) -
                                     std::tan(deg_to_rad(delta_p)) * cos_deg(in.latitude_deg))));
    out.azimuth_deg = limit_degrees(gamma + 180.0);
    return out;
}

double incidence_angle_deg(const SolarPosition& sun, double tilt_deg, double surface_azimuth_deg) {
    if (!std::isfinite(tilt_deg) || !std::isfinite(surface_azimuth_deg))
        fail("surface tilt {}° and azimuth {}°: expected finite angles", tilt_deg,
             surface_azimuth_deg);
    // Eq. 47 with γ (from south) = Γ (from north) − 180°: cos(Γ − 180° − γ_s) = cos(Φ − γ_n).
    const double c = cos_deg(sun.zenith_deg) * cos_deg(tilt_deg) +
                     sin_deg(tilt_deg) * sin_deg(sun.zenith_deg) *
                         cos_deg(sun.azimuth_deg - surface_azimuth_deg);
    return rad_to_deg(std::acos(std::clamp(c, -1.0, 1.0)));
}

Vec3 sun_direction(const SolarPosition& sun) {
    return facet_normal(sun.zenith_deg, sun.azimuth_deg);
}

Vec3 facet_normal(double tilt_deg, double surface_azimuth_deg) {
    return {sin_deg(tilt_deg) * sin_deg(surface_azimuth_deg),
            sin_deg(tilt_deg) * cos_deg(surface_azimuth_deg), cos_deg(tilt_deg)};
}

}  // namespace tirpol::thermal
