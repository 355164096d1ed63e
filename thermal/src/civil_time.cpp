#include "tirpol/thermal/civil_time.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdlib>

#include "tirpol/core/error.h"

namespace tirpol::thermal {

namespace {

// Days since 1970-01-01 of a proleptic Gregorian date (Hinnant's days_from_civil).
long long days_from_civil(long long y, unsigned m, unsigned d) {
    y -= m <= 2 ? 1 : 0;
    const long long era = (y >= 0 ? y : y - 399) / 400;
    const auto yoe = static_cast<unsigned>(y - era * 400);
    const unsigned doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
    const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + static_cast<long long>(doe) - 719468;
}

void civil_from_days(long long z, int& year, int& month, int& day) {
    z += 719468;
    const long long era = (z >= 0 ? z : z - 146096) / 146097;
    const auto doe = static_cast<unsigned>(z - era * 146097);
    const unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    const unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    const unsigned mp = (5 * doy + 2) / 153;
    const unsigned d = doy - (153 * mp + 2) / 5 + 1;
    const unsigned m = mp < 10 ? mp + 3 : mp - 9;
    year = static_cast<int>(static_cast<long long>(yoe) + era * 400 + (m <= 2 ? 1 : 0));
    month = static_cast<int>(m);
    day = static_cast<int>(d);
}

int days_in_month(int year, int month) {
    static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    return month == 2 && leap ? 29 : kDays[month - 1];
}

}  // namespace

double to_unix_seconds(const CivilTime& c) {
    if (c.month < 1 || c.month > 12) fail("invalid month {} (expected 1–12)", c.month);
    if (c.day < 1 || c.day > days_in_month(c.year, c.month))
        fail("invalid day {} for {:04d}-{:02d}", c.day, c.year, c.month);
    if (c.hour < 0 || c.hour > 24 || c.minute < 0 || c.minute > 59 ||
        !(c.second >= 0.0 && c.second < 61.0))
        fail("invalid time of day {:02d}:{:02d}:{}", c.hour, c.minute, c.second);
    const long long days =
        days_from_civil(c.year, static_cast<unsigned>(c.month), static_cast<unsigned>(c.day));
    return static_cast<double>(days) * 86400.0 + c.hour * 3600.0 + c.minute * 60.0 + c.second -
           c.utc_offset_h * 3600.0;
}

CivilTime to_civil(double unix_seconds, double utc_offset_h) {
    const double local = unix_seconds + utc_offset_h * 3600.0;
    const double days = std::floor(local / 86400.0);
    double rest = local - days * 86400.0;
    CivilTime c;
    civil_from_days(static_cast<long long>(days), c.year, c.month, c.day);
    c.hour = static_cast<int>(rest / 3600.0);
    rest -= c.hour * 3600.0;
    c.minute = static_cast<int>(rest / 60.0);
    c.second = rest - c.minute * 60.0;
    c.utc_offset_h = utc_offset_h;
    return c;
}

double julian_day(double unix_seconds) { return unix_seconds / 86400.0 + 2440587.5; }

double parse_time(std::string_view text, double default_utc_offset_h, std::string_view what) {
    const std::string s(text);
    auto bad = [&]() -> double {
        fail(
            "{}: '{}' is not a time; expected YYYY-MM-DDTHH:MM[:SS][Z|±HH:MM], e.g. "
            "2003-10-17T12:30:30-07:00",
            what, s);
    };
    std::size_t pos = 0;
    auto number = [&](std::size_t digits) -> int {
        if (pos + digits > s.size()) bad();
        int v = 0;
        for (std::size_t i = 0; i < digits; ++i) {
            const char ch = s[pos + i];
            if (!std::isdigit(static_cast<unsigned char>(ch))) bad();
            v = v * 10 + (ch - '0');
        }
        pos += digits;
        return v;
    };
    auto expect = [&](char ch) {
        if (pos >= s.size() || s[pos] != ch) bad();
        ++pos;
    };
    CivilTime c;
    c.year = number(4);
    expect('-');
    c.month = number(2);
    expect('-');
    c.day = number(2);
    if (pos >= s.size() || (s[pos] != 'T' && s[pos] != ' ')) bad();
    ++pos;
    c.hour = number(2);
    expect(':');
    c.minute = number(2);
    if (pos < s.size() && s[pos] == ':') {
        ++pos;
        const std::size_t start = pos;
        while (pos < s.size() &&
               (std::isdigit(static_cast<unsigned char>(s[pos])) || s[pos] == '.'))
            ++pos;
        if (pos == start) bad();
        c.second = std::strtod(s.substr(start, pos - start).c_str(), nullptr);
    }
    c.utc_offset_h = default_utc_offset_h;
    if (pos < s.size()) {
        if (s[pos] == 'Z' && pos + 1 == s.size()) {
            c.utc_offset_h = 0.0;
            ++pos;
        } else if (s[pos] == '+' || s[pos] == '-') {
            const double sign = s[pos] == '-' ? -1.0 : 1.0;
            ++pos;
            const int oh = number(2);
            int om = 0;
            if (pos < s.size()) {
                if (s[pos] == ':') ++pos;
                om = number(2);
            }
            c.utc_offset_h = sign * (oh + om / 60.0);
        }
        if (pos != s.size()) bad();
    }
    try {
        return to_unix_seconds(c);
    } catch (const Error& e) {
        fail("{}: '{}': {}", what, s, e.what());
    }
}

std::string format_time(double unix_seconds, double utc_offset_h) {
    // Round to the millisecond first so 59.9999 s does not print as "60".
    const double rounded = std::round(unix_seconds * 1000.0) / 1000.0;
    const CivilTime c = to_civil(rounded, utc_offset_h);
    const double whole = std::floor(c.second + 1e-9);
    const int offset_min = static_cast<int>(std::lround(std::abs(utc_offset_h) * 60.0));
    std::string sec = fmt::format("{:02d}", static_cast<int>(whole));
    const double frac = c.second - whole;
    if (frac > 5e-4) sec += fmt::format("{:.3f}", frac).substr(1);
    return fmt::format("{:04d}-{:02d}-{:02d}T{:02d}:{:02d}:{}{}{:02d}:{:02d}", c.year, c.month,
                       c.day, c.hour, c.minute, sec, utc_offset_h < 0 ? '-' : '+', offset_min / 60,
                       offset_min % 60);
}

}  // namespace tirpol::thermal
