#include "io/utc_time.h"

#include "io/error.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace rk::io {
namespace {

// Reads exactly `n` digits at text[*i].
bool Digits(std::string_view text, std::size_t* i, std::size_t n, int* value) {
  if (*i + n > text.size()) return false;
  int v = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const char c = text[*i + k];
    if (c < '0' || c > '9') return false;
    v = v * 10 + (c - '0');
  }
  *i += n;
  *value = v;
  return true;
}

bool Expect(std::string_view text, std::size_t* i, char c) {
  if (*i >= text.size() || text[*i] != c) return false;
  ++*i;
  return true;
}

int DaysInMonth(int year, int month) {
  static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  return month == 2 && leap ? 29 : kDays[month - 1];
}

}  // namespace

bool ParseUtcIso(std::string_view text, UtcTime* out, std::string* why) {
  const auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  UtcTime t;
  std::size_t i = 0;
  if (!Digits(text, &i, 4, &t.year) || !Expect(text, &i, '-') || !Digits(text, &i, 2, &t.month) ||
      !Expect(text, &i, '-') || !Digits(text, &i, 2, &t.day) || !Expect(text, &i, 'T') ||
      !Digits(text, &i, 2, &t.hour) || !Expect(text, &i, ':') || !Digits(text, &i, 2, &t.minute) ||
      !Expect(text, &i, ':')) {
    return fail("not of the form " + std::string(kUtcIsoFormat));
  }
  int whole = 0;
  if (!Digits(text, &i, 2, &whole)) return fail("not of the form " + std::string(kUtcIsoFormat));
  double fraction = 0.0;
  if (i < text.size() && text[i] == '.') {
    const std::size_t start = i;
    ++i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
    if (i == start + 1) return fail("a decimal point with no digits after it");
    std::from_chars(text.data() + start, text.data() + i, fraction);  // "0.fff" without the 0: from_chars reads ".fff"
  }
  if (i < text.size() && text[i] == 'Z') ++i;
  if (i != text.size()) {
    const char c = text[i];
    if (c == '+' || c == '-') return fail("a time-zone offset: write the time in UTC with Z");
    return fail("unexpected '" + std::string(text.substr(i)) + "' after the seconds");
  }
  if (t.month < 1 || t.month > 12) return fail("month " + std::to_string(t.month) + " is out of range");
  if (t.day < 1 || t.day > DaysInMonth(t.year, t.month)) {
    return fail("day " + std::to_string(t.day) + " does not exist in month " + std::to_string(t.month));
  }
  if (t.hour > 23) return fail("hour " + std::to_string(t.hour) + " is out of range");
  if (t.minute > 59) return fail("minute " + std::to_string(t.minute) + " is out of range");
  const bool leap_second_slot = t.hour == 23 && t.minute == 59 &&
                                ((t.month == 6 && t.day == 30) || (t.month == 12 && t.day == 31));
  if (whole > 60 || (whole == 60 && !leap_second_slot)) {
    return fail("second " + std::to_string(whole) + " is out of range (60 only for a leap second at 23:59:60 on "
                "30 June or 31 December)");
  }
  t.second = whole + fraction;
  *out = t;
  return true;
}

double UnixSeconds(const UtcTime& t) {
  // Days from the civil date (proleptic Gregorian), H. Hinnant's algorithm.
  const int y = t.year - (t.month <= 2 ? 1 : 0);
  const int era = (y >= 0 ? y : y - 399) / 400;
  const int yoe = y - era * 400;
  const int mp = (t.month + 9) % 12;
  const int doy = (153 * mp + 2) / 5 + t.day - 1;
  const int doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  const long long days = static_cast<long long>(era) * 146097 + doe - 719468;
  return static_cast<double>(days) * 86400.0 + t.hour * 3600.0 + t.minute * 60.0 + t.second;
}

std::string FormatUtcIso(double unix_s, int decimals, Rounding rounding) {
  RK_CHECK(decimals >= 0 && decimals <= 6 && std::isfinite(unix_s), "FormatUtcIso: decimals in [0, 6], a finite time");
  long long scale = 1;
  for (int k = 0; k < decimals; ++k) scale *= 10;
  const double scaled = unix_s * static_cast<double>(scale);
  const double whole = rounding == Rounding::kDown ? std::floor(scaled)
                       : rounding == Rounding::kUp ? std::ceil(scaled)
                                                   : std::round(scaled);
  const long long units = static_cast<long long>(whole);
  const long long per_day = 86400LL * scale;
  long long days = units / per_day, rest = units % per_day;
  if (rest < 0) {
    rest += per_day;
    --days;
  }
  // The civil date of a day count (proleptic Gregorian), H. Hinnant's algorithm (the inverse of UnixSeconds').
  const long long z = days + 719468;
  const long long era = (z >= 0 ? z : z - 146096) / 146097;
  const long long doe = z - era * 146097;
  const long long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const long long doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const long long mp = (5 * doy + 2) / 153;
  const long long day = doy - (153 * mp + 2) / 5 + 1;
  const long long month = mp < 10 ? mp + 3 : mp - 9;
  const long long year = yoe + era * 400 + (month <= 2 ? 1 : 0);
  const long long second_units = rest % (60 * scale);
  const long long minutes = rest / (60 * scale);
  char text[64];
  int n = std::snprintf(text, sizeof text, "%04lld-%02lld-%02lldT%02lld:%02lld:%02lld", year, month, day, minutes / 60,
                        minutes % 60, second_units / scale);
  if (decimals > 0) {
    n += std::snprintf(text + n, sizeof text - static_cast<std::size_t>(n), ".%0*lld", decimals, second_units % scale);
  }
  std::snprintf(text + n, sizeof text - static_cast<std::size_t>(n), "Z");
  return text;
}

std::optional<double> ParseEpochOption(const std::string& text, const std::string& option) {
  if (text.empty()) return std::nullopt;
  UtcTime t;
  std::string why;
  if (!ParseUtcIso(text, &t, &why)) {
    throw UsageError(option + " '" + text + "': " + why + "; expected " + kUtcIsoFormat);
  }
  return UnixSeconds(t);
}

}  // namespace rk::io
