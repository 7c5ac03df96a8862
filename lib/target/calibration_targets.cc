#include "target/calibration_targets.h"

#include "io/utc_time.h"

#include <erfa.h>

#include <cmath>
#include <cstdio>
#include <set>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::target {
namespace {

constexpr double kMasToRad = geo::DegToRad(1.0) / 3.6e6;
constexpr double kMinLandmarkRangeM = 1.0;  // a landmark closer than this has no usable direction

// The station-ENU position of one landmark row (WGS-84 or ENU columns).
Eigen::Vector3d LandmarkEnu(const io::CsvTable& t, std::size_t r, const geo::LocalEnu& station, bool geodetic) {
  if (geodetic) {
    const int clat = t.RequireColumn("lat_deg"), clon = t.RequireColumn("lon_deg"), ch = t.RequireColumn("h_m");
    const double lat = t.Double(r, clat);
    if (std::abs(lat) > 90.0) throw t.CellError(r, clat, "lat_deg must be in [-90, 90]");
    return station.ToEnu({lat, t.Double(r, clon), t.Double(r, ch)});
  }
  return {t.Double(r, t.RequireColumn("e_m")), t.Double(r, t.RequireColumn("n_m")),
          t.Double(r, t.RequireColumn("u_m"))};
}

}  // namespace

std::vector<Landmark> ReadLandmarks(const io::CsvTable& t, const Geodetic& station) {
  const int cid = t.RequireColumn("id");
  const bool geodetic = t.HasColumn("lat_deg") || t.HasColumn("lon_deg");
  if (!geodetic && !t.HasColumn("e_m")) {
    throw DataError(t.name(), t.header_line(), 1, "landmarks need columns lat_deg,lon_deg,h_m or e_m,n_m,u_m");
  }
  const int csig = t.Column("sigma_m");
  std::vector<Landmark> out;
  std::set<std::string> seen;
  const geo::LocalEnu enu(station);
  for (std::size_t r = 0; r < t.rows(); ++r) {
    Landmark l;
    l.id = std::string(t.Cell(r, cid));
    l.line = t.Line(r);
    if (l.id.empty()) throw t.CellError(r, cid, "empty landmark id");
    if (!seen.insert(l.id).second) throw t.CellError(r, cid, "duplicate landmark id '" + l.id + "'");
    l.p_enu = LandmarkEnu(t, r, enu, geodetic);
    if (l.p_enu.norm() < kMinLandmarkRangeM) {
      throw t.CellError(r, cid, "landmark '" + l.id + "' is within 1 m of the station");
    }
    if (csig >= 0) {
      l.sigma_m = t.OptionalDouble(r, csig).value_or(0.0);
      if (l.sigma_m < 0.0) throw t.CellError(r, csig, "sigma_m must be >= 0");
    }
    out.push_back(l);
  }
  return out;
}

std::vector<Star> ReadStars(const io::CsvTable& t) {
  const int cid = t.RequireColumn("id"), cra = t.RequireColumn("ra_deg"), cdec = t.RequireColumn("dec_deg");
  const int cpmr = t.Column("pm_ra_mas_yr"), cpmd = t.Column("pm_dec_mas_yr"), cpx = t.Column("parallax_mas");
  const int crv = t.Column("rv_kms"), cmag = t.Column("mag");
  auto opt = [&](std::size_t r, int c) { return c >= 0 ? t.OptionalDouble(r, c).value_or(0.0) : 0.0; };
  std::vector<Star> out;
  std::set<std::string> seen;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    Star s;
    s.id = std::string(t.Cell(r, cid));
    s.line = t.Line(r);
    if (s.id.empty()) throw t.CellError(r, cid, "empty star id");
    if (!seen.insert(s.id).second) throw t.CellError(r, cid, "duplicate star id '" + s.id + "'");
    const double ra = t.Double(r, cra), dec = t.Double(r, cdec);
    if (ra < 0.0 || ra >= 360.0) throw t.CellError(r, cra, "ra_deg must be in [0, 360)");
    if (std::abs(dec) > 90.0) throw t.CellError(r, cdec, "dec_deg must be in [-90, 90]");
    s.ra_rad = geo::DegToRad(ra);
    s.dec_rad = geo::DegToRad(dec);
    s.pm_ra_cosdec_mas_yr = opt(r, cpmr);
    s.pm_dec_mas_yr = opt(r, cpmd);
    s.parallax_mas = opt(r, cpx);
    if (s.parallax_mas < 0.0) throw t.CellError(r, cpx, "parallax_mas must be >= 0");
    s.rv_kms = opt(r, crv);
    if (cmag >= 0) s.mag = t.OptionalDouble(r, cmag);
    out.push_back(s);
  }
  return out;
}

UtcJd ParseUtc(const std::string& iso, const std::string& what) {
  io::UtcTime t;
  std::string why;
  UtcJd u;
  if (!io::ParseUtcIso(iso, &t, &why) ||
      eraDtf2d("UTC", t.year, t.month, t.day, t.hour, t.minute, t.second, &u.jd1, &u.jd2) < 0) {
    throw UsageError(what + " must be an ISO-8601 UTC time " + io::kUtcIsoFormat + ", got '" + iso + "'" +
                     (why.empty() ? "" : ": " + why));
  }
  return u;
}

std::string FormatUtc(const UtcJd& utc) {
  int y = 0, mo = 0, d = 0, hmsf[4] = {0, 0, 0, 0};
  if (eraD2dtf("UTC", 3, utc.jd1, utc.jd2, &y, &mo, &d, hmsf) < 0) return "";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", y, mo, d, hmsf[0], hmsf[1], hmsf[2], hmsf[3]);
  return buf;
}

ObservedPlace StarObservedPlace(const Star& s, const Geodetic& st, const UtcJd& utc, double dut1_s,
                                const Atmosphere& a) {
  // ERFA wants dRA/dt (not μα·cos δ) in radians per Julian year and the parallax in arcseconds.
  const double cos_dec = std::max(std::cos(s.dec_rad), 1e-12);
  const double pr = s.pm_ra_cosdec_mas_yr * kMasToRad / cos_dec, pd = s.pm_dec_mas_yr * kMasToRad;
  double aob = 0, zob = 0, hob = 0, dob = 0, rob = 0, eo = 0;
  const int j = eraAtco13(s.ra_rad, s.dec_rad, pr, pd, s.parallax_mas * 1e-3, s.rv_kms, utc.jd1, utc.jd2, dut1_s,
                          geo::DegToRad(st.lon_deg), geo::DegToRad(st.lat_deg), st.h_m, 0.0, 0.0, a.pressure_hpa, a.temperature_c, a.humidity,
                          a.wavelength_um, &aob, &zob, &hob, &dob, &rob, &eo);
  if (j < 0) throw ProcessingError("ERFA cannot compute the observed place of star '" + s.id + "' (bad date)");
  return {eraAnp(aob), M_PI / 2 - zob};
}

Star StarFromObservedPlace(const std::string& id, const ObservedPlace& o, const Geodetic& st, const UtcJd& utc,
                           double dut1_s, const Atmosphere& a) {
  Star s;
  s.id = id;
  const int j = eraAtoc13("A", o.az_rad, M_PI / 2 - o.el_rad, utc.jd1, utc.jd2, dut1_s, geo::DegToRad(st.lon_deg),
                          geo::DegToRad(st.lat_deg), st.h_m, 0.0, 0.0, a.pressure_hpa, a.temperature_c, a.humidity, a.wavelength_um, &s.ra_rad,
                          &s.dec_rad);
  if (j < 0) throw ProcessingError("ERFA cannot compute the catalogue place of star '" + id + "' (bad date)");
  s.ra_rad = eraAnp(s.ra_rad);
  return s;
}

Eigen::Vector3d DirectionEnu(double az_rad, double el_rad) {
  return {std::sin(az_rad) * std::cos(el_rad), std::cos(az_rad) * std::cos(el_rad), std::sin(el_rad)};
}

}  // namespace rk::target
