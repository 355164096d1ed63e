#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"

namespace tirpol {

double check_temperature_k(double temperature_k, std::string_view what) {
    if (!(temperature_k >= limits::kMinTemperatureK && temperature_k <= limits::kMaxTemperatureK))
        fail("{}: temperature {} K is outside the physical range tirpol accepts, [{}, {}] K", what,
             temperature_k, limits::kMinTemperatureK, limits::kMaxTemperatureK);
    return temperature_k;
}

double check_finite(double value, std::string_view what) {
    if (!std::isfinite(value))
        fail(
            "{}: the result is not a finite number ({}); an input is outside the range the "
            "computation can "
            "represent",
            what, value);
    return value;
}

double check_non_negative(double value, std::string_view what) {
    if (!(std::isfinite(value) && value >= 0.0))
        fail("{}: expected a finite number ≥ 0, got {}", what, value);
    return value;
}

}  // namespace tirpol
