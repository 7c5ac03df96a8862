// The one reader of an ISO-8601 UTC time (trial.json "epoch_utc", rk-sim --epoch, rk-calibrate pointing
// --utc): YYYY-MM-DDThh:mm:ss[.fff][Z], every field in range (a real calendar day; second 60 only at
// 23:59:60 on 30 June or 31 December, where leap seconds are inserted). Offsets (+01:00) are refused:
// the files and options are UTC by name.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace rk::io {

struct UtcTime {
  int year = 0, month = 0, day = 0, hour = 0, minute = 0;
  double second = 0.0;
};

// True and *out on success; false and *why (a phrase: "month 13 is out of range") otherwise.
bool ParseUtcIso(std::string_view text, UtcTime* out, std::string* why);

// Seconds since 1970-01-01T00:00:00Z (POSIX time: a leap second 23:59:60 counts as the next day's 00:00:00),
// to compare with a recording's own UTC stamps (CINE time blocks, IRIG).
double UnixSeconds(const UtcTime& t);

// An option's ISO-8601 UTC value (--epoch-utc) as POSIX seconds (nullopt for ""); UsageError naming the option
// when it is not ISO-8601 UTC.
std::optional<double> ParseEpochOption(const std::string& text, const std::string& option = "--epoch-utc");

// The ISO-8601 UTC text of POSIX seconds `unix_s` with `decimals` (0 to 6) digits of the second and a Z:
// 2026-01-01T00:00:01.250Z. Rounded to the nearest unit of the last digit, or down or up (the start and stop of an
// interval that must hold a time). POSIX time has no leap second: none is ever written as 23:59:60.
enum class Rounding { kNearest, kDown, kUp };
std::string FormatUtcIso(double unix_s, int decimals, Rounding rounding = Rounding::kNearest);

// The format in words, for messages.
inline constexpr const char* kUtcIsoFormat = "YYYY-MM-DDThh:mm:ss[.fff]Z (UTC, e.g. 2026-11-21T08:00:00Z)";

}  // namespace rk::io
