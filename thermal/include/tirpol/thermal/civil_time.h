#pragma once
/// \file civil_time.h
/// Instants as seconds since 1970-01-01T00:00:00 UTC (a double, so sub-second times and the SPA's
/// fractional Julian days are exact enough), converted from and to civil dates with a UTC offset.
/// Proleptic Gregorian calendar (days-from-civil algorithm of H. Hinnant, "chrono-compatible
/// low-level date algorithms"). No leap seconds (UTC is treated as uniform, as the SPA report
/// does).

#include <string>
#include <string_view>

namespace tirpol::thermal {

/// A civil date and time at some UTC offset.
struct CivilTime {
    int year = 2000;
    int month = 1;   ///< 1–12
    int day = 1;     ///< 1–31
    int hour = 0;    ///< 0–24 (24:00 is accepted: the end of the day, as in EPW files)
    int minute = 0;  ///< 0–59
    double second = 0.0;
    double utc_offset_h = 0.0;  ///< local time − UTC, hours (UTC−7 → −7)
};

/// Seconds since the Unix epoch (UTC) of a civil time. Throws tirpol::Error for an invalid date.
double to_unix_seconds(const CivilTime& civil);

/// The civil time of `unix_seconds` at `utc_offset_h`.
CivilTime to_civil(double unix_seconds, double utc_offset_h);

/// Julian Day (UT) of an instant: JD = t/86400 + 2440587.5 (Reda & Andreas 2003, eq. 4, gives the
/// same value for Gregorian dates).
double julian_day(double unix_seconds);

/// Parses "YYYY-MM-DD[T| ]HH:MM[:SS[.fff]][Z|±HH[:MM]]". Without an explicit offset the time is
/// local at `default_utc_offset_h`. Throws tirpol::Error naming `what` (e.g. "--at") and the text.
double parse_time(std::string_view text, double default_utc_offset_h,
                  std::string_view what = "time");

/// ISO 8601 text of an instant at `utc_offset_h`, e.g. "2003-10-17T12:30:30-07:00".
std::string format_time(double unix_seconds, double utc_offset_h);

}  // namespace tirpol::thermal
