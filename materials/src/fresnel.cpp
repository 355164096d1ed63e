#include "tirpol/materials/fresnel.h"

#include <algorithm>

namespace tirpol::materials {

FresnelResult fresnel(const ComplexIndex& index, double cos_i) {
    const double c = std::clamp(cos_i, 0.0, 1.0);
    const FresnelAmplitudes<double> a = fresnel_amplitudes(index.n, index.k, c);
    FresnelResult r;
    r.rs = {a.rs.re, a.rs.im};
    r.rp = {a.rp.re, a.rp.im};
    r.Rs = norm2(a.rs);
    r.Rp = norm2(a.rp);
    return r;
}

MuellerMatrix fresnel_mueller(const ComplexIndex& index, double cos_i) {
    const Mueller4<double> m = fresnel_mueller_t(index.n, index.k, std::clamp(cos_i, 0.0, 1.0));
    MuellerMatrix out;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            out(r, c) = m[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
    return out;
}

}  // namespace tirpol::materials
