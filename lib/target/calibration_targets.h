// Calibration targets of SPEC.md §3.1 and their directions seen from the station: the forward model that
// rk-calibrate pointing (estimator) and rk-sim pointing (simulator) share, so it lives here, below both.
//
// Landmarks (SPEC.md §2.1 `id,lat_deg,lon_deg,h_m` WGS-84 ellipsoidal, or `id,e_m,n_m,u_m` station ENU;
// optional `sigma_m`): station-ENU position by geo::LocalEnu at the station's WGS-84
// position; no refraction (ranges below 2 km).
// Stars (`id,ra_deg,dec_deg` ICRS catalogue place at J2000.0; optional `pm_ra_mas_yr` = μα·cos δ,
// `pm_dec_mas_yr`, `parallax_mas`, `rv_kms`, `mag`): observed (topocentric, refracted) azimuth and
// elevation at a UTC by ERFA eraAtco13 (IAU 2006/2000A, proper motion, parallax, radial velocity, aberration,
// light deflection, refraction for the given pressure, temperature, humidity and wavelength), with
// UT1−UTC = dut1 and polar motion 0 (SPEC.md §3.1).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "geo/wgs84.h"
#include "io/csv.h"

namespace rk::target {

using geo::Geodetic;  // the station's WGS-84 position (geo/wgs84.h; degrees, metres)

struct Landmark {
  std::string id;
  Eigen::Vector3d p_enu = Eigen::Vector3d::Zero();  // station ENU (m)
  double sigma_m = 0.0;                             // 1σ of the surveyed position per axis (m), 0 = exact
  std::size_t line = 0;                             // line in the landmarks file
};
// Reads a landmarks table; positions in station ENU. DataError at file:line:col for a bad cell, a duplicate
// id, neither column set present, or a landmark at the station (closer than 1 m).
std::vector<Landmark> ReadLandmarks(const io::CsvTable& table, const Geodetic& station);

struct Star {
  std::string id;
  double ra_rad = 0.0, dec_rad = 0.0;  // ICRS catalogue place at J2000.0
  double pm_ra_cosdec_mas_yr = 0.0;    // μα·cos δ
  double pm_dec_mas_yr = 0.0;
  double parallax_mas = 0.0;
  double rv_kms = 0.0;
  std::optional<double> mag;
  std::size_t line = 0;
};
std::vector<Star> ReadStars(const io::CsvTable& table);

// Observing conditions for the refraction (SPEC.md §3.1 defaults).
struct Atmosphere {
  double pressure_hpa = 1013.25;
  double temperature_c = 10.0;
  double humidity = 0.5;  // relative, 0..1
  double wavelength_um = 0.85;
};

// A UTC instant as ERFA's two-part quasi-Julian date.
struct UtcJd {
  double jd1 = 0.0, jd2 = 0.0;
  // The instant `seconds` later (a leap second inside the interval is ignored).
  UtcJd Plus(double seconds) const { return {jd1, jd2 + seconds / 86400.0}; }
};
// "YYYY-MM-DDThh:mm:ss[.fff][Z]" (UTC). Throws UsageError naming `what` for anything else.
UtcJd ParseUtc(const std::string& iso, const std::string& what);
std::string FormatUtc(const UtcJd& utc);

// Observed azimuth (clockwise from true north, [0, 2π)) and elevation (radians, refracted) of a star.
// Throws ProcessingError if ERFA refuses the date.
struct ObservedPlace {
  double az_rad = 0.0, el_rad = 0.0;
};
ObservedPlace StarObservedPlace(const Star& star, const Geodetic& station, const UtcJd& utc, double dut1_s,
                                const Atmosphere& atmosphere);
// The ICRS catalogue place (no proper motion, parallax or radial velocity) of a star observed at az/el at
// `utc` (ERFA eraAtoc13; the inverse of StarObservedPlace to ~1 mas): the simulator's way to make a star
// catalogue whose stars stand where it wants them.
Star StarFromObservedPlace(const std::string& id, const ObservedPlace& observed, const Geodetic& station,
                           const UtcJd& utc, double dut1_s, const Atmosphere& atmosphere);

// Unit ENU vector of an azimuth/elevation (radians).
Eigen::Vector3d DirectionEnu(double az_rad, double el_rad);

}  // namespace rk::target
