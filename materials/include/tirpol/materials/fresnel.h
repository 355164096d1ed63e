#pragma once
/// \file fresnel.h
/// Fresnel reflection at a smooth interface from air (index 1) into a medium of complex index
/// ñ = n + i·k (complex_index.h: waves ∝ exp(i(k·r − ωt)), k ≥ 0 absorbing).
///
/// With c = cos θi, s² = 1 − c² and q = ñ·cos θt = √(ñ² − s²) (principal root, Re q ≥ 0, Im q ≥ 0):
///   r_s = (c − q) / (c + q),      r_p = (ñ²·c − q) / (ñ²·c + q)
/// (Born & Wolf, Principles of Optics, 7th ed., §1.5.2 eq 21 and §14.2 for absorbing media).
/// These are the Jones matrix J = diag(r_s, r_p) of reflection in tirpol's s/p frames (pbrdf.h):
/// incident Stokes in surface_frame(−wi, n), reflected in surface_frame(wo, n), both with reference
/// axis s = n × k. In these frames p-light at normal incidence comes back with r_p = −r_s (the
/// frames' p axes point in opposite directions in space while the physical field flips with r_s).
///
/// Time convention of the Jones→Mueller conversion: r_s, r_p above are amplitudes for waves
/// ∝ exp(i(k·r − ωt)) (ñ = n + ik). core's mueller_from_jones and stokes.h use the opposite one,
/// exp(i(ωt − k·r)), in which σ3 = [[0,−i],[i,0]] gives S3 > 0 for right-circular light as seen by
/// the receiver (mueller.h). A Jones matrix changes convention by complex conjugation, so the
/// Mueller matrix is mueller_from_jones(diag(r_s*, r_p*)) (Chipman et al. 2018 eq 6.99), with Rs =
/// |r_s|², Rp = |r_p|² and c = r_s*·r_p:
///   [ (Rs+Rp)/2  (Rs−Rp)/2      0        0    ]
///   [ (Rs−Rp)/2  (Rs+Rp)/2      0        0    ]
///   [     0          0        Re c     Im c   ]
///   [     0          0       −Im c     Re c   ]
/// m01 > 0: reflection favours s (S1 > 0); the 2×2 lower block is the retardance δ = arg(r_p/r_s).
/// Pinned by tests/materials/fresnel_test.cpp (Fresnel rhomb: Born & Wolf §1.5.4 eq 60 and Hecht,
/// Optics §8.7; +45° linear light leaves right-circular, S3 > 0).
///
/// The formulas are templates on the scalar type T (double or ceres::Jet) using TinyComplex, so the
/// fitting module can differentiate them; the cosine of incidence may be a plain double.
///
/// A minimal complex number templated on its scalar, so that Fresnel and micro-facet formulas can
/// be evaluated with ceres::Jet (std::complex<Jet> is not supported by Ceres, DEPENDENCIES.md).
/// Only the operations the materials formulas need. Functions call sqrt/abs unqualified so that
/// argument-dependent lookup finds ceres::sqrt for Jets.
///
/// Complex index of refraction ñ = n + i·k of a material relative to the incidence medium (air,
/// taken as 1), as a function of wavelength in micrometres.
///
/// Convention (used by every Fresnel formula in tirpol): plane waves E ∝ exp(i(k·r − ωt)) and
/// ñ = n + i·k with k ≥ 0 for an absorbing medium: the convention of refractiveindex.info, Palik's
/// Handbook of Optical Constants of Solids (1985) and Hale & Querry (1973).

#include <array>
#include <cmath>
#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include "tirpol/core/stokes.h"

namespace tirpol::materials {

/// n + i·k; k ≥ 0 means absorption.
struct ComplexIndex {
    double n = 1.0;
    double k = 0.0;
};

/// A tabulated (or constant) complex index, linearly interpolated in wavelength.
class RefractiveIndexTable {
public:
    /// A wavelength-independent index (valid at every wavelength).
    static RefractiveIndexTable constant(ComplexIndex index, std::string source = "constant");

    /// Tabulated values; wavelengths strictly increasing, n > 0, k ≥ 0. `source` names where the
    /// data came from (used in error messages).
    RefractiveIndexTable(std::vector<double> wavelength_um, std::vector<double> n,
                         std::vector<double> k, std::string source);

    /// Loads a refractiveindex.info database file (YAML with `DATA: - type: tabulated nk` and a
    /// `data:` block of "λ_µm n k" rows; also `tabulated n` + `tabulated k` pairs), or a CSV with a
    /// header naming wavelength_um, n, k ('#' comment lines allowed). Chosen by extension
    /// (.yml/.yaml vs .csv). Errors name the file and line.
    static RefractiveIndexTable load(const std::filesystem::path& path);

    /// Index at `wavelength_um`; throws tirpol::Error naming the source and its range outside it.
    ComplexIndex at(double wavelength_um) const;

    /// Index at `wavelength_um`, clamped to the table's ends (for hot loops whose range was checked
    /// with `covers` beforehand). Never throws.
    ComplexIndex at_clamped(double wavelength_um) const;

    /// True if [lo_um, hi_um] lies inside the table's range.
    bool covers(double lo_um, double hi_um) const;

    bool is_constant() const { return m_wavelength_um.empty(); }
    double min_wavelength_um() const;
    double max_wavelength_um() const;
    const std::string& source() const { return m_source; }
    const std::vector<double>& wavelengths_um() const { return m_wavelength_um; }

private:
    RefractiveIndexTable() = default;
    std::vector<double> m_wavelength_um, m_n, m_k;
    ComplexIndex m_constant;
    std::string m_source;
};

template <typename T>
struct TinyComplex {
    T re;
    T im;
};

template <typename T>
TinyComplex<T> operator+(const TinyComplex<T>& a, const TinyComplex<T>& b) {
    return {a.re + b.re, a.im + b.im};
}
template <typename T>
TinyComplex<T> operator-(const TinyComplex<T>& a, const TinyComplex<T>& b) {
    return {a.re - b.re, a.im - b.im};
}
template <typename T>
TinyComplex<T> operator*(const TinyComplex<T>& a, const TinyComplex<T>& b) {
    return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}
/// Complex times real.
template <typename T, typename S>
TinyComplex<T> scale(const TinyComplex<T>& a, const S& s) {
    return {a.re * s, a.im * s};
}
template <typename T>
TinyComplex<T> conj(const TinyComplex<T>& a) {
    return {a.re, -a.im};
}
/// |a|².
template <typename T>
T norm2(const TinyComplex<T>& a) {
    return a.re * a.re + a.im * a.im;
}
template <typename T>
TinyComplex<T> operator/(const TinyComplex<T>& a, const TinyComplex<T>& b) {
    const T d = norm2(b);
    return {(a.re * b.re + a.im * b.im) / d, (a.im * b.re - a.re * b.im) / d};
}

/// Principal square root (Re ≥ 0; for a negative real argument the result is +i·√|a|). Written in
/// the cancellation-free form: the larger of the two parts is computed from √((|a| ± re)/2), the
/// other as im/(2·larger), so the derivative stays finite everywhere except at a = 0.
template <typename T>
TinyComplex<T> csqrt(const TinyComplex<T>& a) {
    using std::sqrt;
    const T r = sqrt(a.re * a.re + a.im * a.im);
    if (r == T(0)) return {T(0), T(0)};
    if (a.re >= T(0)) {
        const T x = sqrt((r + a.re) * T(0.5));
        return {x, a.im / (T(2) * x)};
    }
    T y = sqrt((r - a.re) * T(0.5));
    if (a.im < T(0)) y = -y;
    return {a.im / (T(2) * y), y};
}

/// 4×4 Mueller matrix for any scalar type (row-major: m[row][col]).
template <typename T>
using Mueller4 = std::array<std::array<T, 4>, 4>;

template <typename T>
struct FresnelAmplitudes {
    TinyComplex<T> rs;
    TinyComplex<T> rp;
};

/// The numerators and denominators of r_s, r_p (file comment) for ñ² = `eps` at cosine of incidence
/// `cos_i` ∈ [0, 1] (T or double): the one place the Fresnel equations are written.
template <typename T>
struct FresnelFractions {
    TinyComplex<T> rs_num, rs_den, rp_num, rp_den;
};

template <typename T, typename C>
FresnelFractions<T> fresnel_fractions(const TinyComplex<T>& eps, const C& cos_i) {
    const TinyComplex<T> c{T(cos_i), T(0)};
    const TinyComplex<T> q =
        csqrt(TinyComplex<T>{eps.re - T(1.0 - cos_i * cos_i), eps.im});  // ñ·cosθt
    const TinyComplex<T> eps_c = scale(eps, cos_i);
    return {c - q, c + q, eps_c - q, eps_c + q};
}

/// Amplitude reflection coefficients for index n + i·k at cosine of incidence `cos_i` ∈ [0, 1].
template <typename T, typename C>
FresnelAmplitudes<T> fresnel_amplitudes(const T& n, const T& k, const C& cos_i) {
    const FresnelFractions<T> f =
        fresnel_fractions(TinyComplex<T>{n * n - k * k, T(2) * n * k}, cos_i);
    return {f.rs_num / f.rs_den, f.rp_num / f.rp_den};
}

/// Reflectances Rs = |r_s|², Rp = |r_p|² for ñ² = `eps` (computed once per parameter set by a
/// caller that loops over angles), as |num|²/|den|² without a complex division.
template <typename T>
struct FresnelReflectances {
    T rs2, rp2;
};

template <typename T, typename C>
FresnelReflectances<T> fresnel_reflectances(const TinyComplex<T>& eps, const C& cos_i) {
    const FresnelFractions<T> f = fresnel_fractions(eps, cos_i);
    return {norm2(f.rs_num) / norm2(f.rs_den), norm2(f.rp_num) / norm2(f.rp_den)};
}

/// Mueller matrix of specular reflection in the s/p frames (file comment), templated.
template <typename T, typename C>
Mueller4<T> fresnel_mueller_t(const T& n, const T& k, const C& cos_i) {
    const FresnelAmplitudes<T> r = fresnel_amplitudes(n, k, cos_i);
    const T rs2 = norm2(r.rs), rp2 = norm2(r.rp);
    // exp(i(k·r − ωt)) amplitudes → the exp(i(ωt − k·r)) Mueller convention: conjugate (file
    // comment).
    const TinyComplex<T> cross = conj(r.rs) * r.rp;
    const T a = (rs2 + rp2) * T(0.5), b = (rs2 - rp2) * T(0.5);
    const T zero(0);
    return {{{a, b, zero, zero},
             {b, a, zero, zero},
             {zero, zero, cross.re, cross.im},
             {zero, zero, -cross.im, cross.re}}};
}

/// Double-precision results at one angle.
struct FresnelResult {
    std::complex<double> rs, rp;  ///< amplitude coefficients (file comment)
    double Rs = 0.0, Rp = 0.0;    ///< reflectances |r|²
    /// Unpolarized reflectance (Rs + Rp)/2.
    double R() const { return 0.5 * (Rs + Rp); }
};

/// Fresnel coefficients for `index` at cosine of incidence `cos_i` (clamped to [0, 1]).
FresnelResult fresnel(const ComplexIndex& index, double cos_i);

/// Mueller matrix of specular reflection (file comment) at cosine of incidence `cos_i`.
MuellerMatrix fresnel_mueller(const ComplexIndex& index, double cos_i);

}  // namespace tirpol::materials
