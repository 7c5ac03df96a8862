#include "io/options.h"

#include <cstdio>

namespace rk::io {
namespace {

std::string G(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

}  // namespace

bool Bounds::Contains(double x) const {
  if (std::isnan(x) || (finite && std::isinf(x))) return false;
  if (std::isfinite(lo) && (lo_open ? !(x > lo) : !(x >= lo))) return false;
  if (std::isfinite(hi) && (hi_open ? !(x < hi) : !(x <= hi))) return false;
  // An infinite value passes only on a side left unbounded.
  if (std::isinf(x) && ((x > 0 && std::isfinite(hi)) || (x < 0 && std::isfinite(lo)))) return false;
  return true;
}

std::string Bounds::Describe() const {
  const std::string prefix = finite ? "finite and " : "";
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi) {
    return prefix + "in " + (lo_open ? "(" : "[") + G(lo) + ", " + G(hi) + (hi_open ? ")" : "]");
  }
  if (has_lo) return prefix + (lo_open ? "> " : ">= ") + G(lo);
  if (has_hi) return prefix + (hi_open ? "< " : "<= ") + G(hi);
  return finite ? "a finite number" : "a number";
}

std::string ReportKey(const std::string& flag, const std::string& unit) {
  std::string key = flag.substr(flag.find_first_not_of('-'));
  for (char& c : key) {
    if (c == '-') c = '_';
  }
  static const char* const kSuffixUnits[] = {"s", "px", "m", "deg", "hz", "dn", "mm", "arcsec"};
  for (const char* u : kSuffixUnits) {
    if (unit != u) continue;
    const std::string suffix = std::string("_") + u;
    if (key.size() < suffix.size() || key.compare(key.size() - suffix.size(), suffix.size(), suffix) != 0) {
      key += suffix;
    }
  }
  return key;
}

}  // namespace rk::io
