#pragma once
/// \file tiny_complex.h
/// A minimal complex number templated on its scalar, so that Fresnel and micro-facet formulas can
/// be evaluated with ceres::Jet (std::complex<Jet> is not supported by Ceres, DEPENDENCIES.md).
/// Only the operations the materials formulas need. Functions call sqrt/abs unqualified so that
/// argument-dependent lookup finds ceres::sqrt for Jets.

#include <cmath>

namespace tirpol::materials {

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

}  // namespace tirpol::materials
