// --station LAT,LON,H (degrees, degrees, metres) in every tool that takes it: rk-locate, rk-calibrate
// pointing, rk-sim pointing. The one parser is geo::ParseGeodetic; this makes its reason a usage error.
#pragma once

#include <string>

#include "geo/wgs84.h"
#include "io/error.h"

namespace rk::cli {

inline geo::Geodetic ParseStationOption(const std::string& text) {
  geo::Geodetic g;
  std::string why;
  if (!geo::ParseGeodetic(text, &g, &why)) throw UsageError("--station: " + why);
  return g;
}

}  // namespace rk::cli
