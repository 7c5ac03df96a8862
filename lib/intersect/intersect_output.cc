// rk-intersect's trajectory CSV (formats/trajectory.h) and report; columns in docs/rk-intersect.md "Columns".
#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "formats/trajectory.h"
#include "intersect/intersect_common.h"
#include "intersect/intersect.h"
#include "io/error.h"

namespace rk::intersect {
namespace {

constexpr int kLengthDecimals = 4;  // 0.1 mm
constexpr int kDegDecimals = 9;     // ~0.1 mm on the earth
constexpr int kFigureDecimals = 4;

io::Json NumberOrNull(double x) { return std::isfinite(x) ? io::Json(x) : io::Json(nullptr); }

void AddVector(io::CsvWriter* w, bool have, const Eigen::Vector3d& v, int decimals) {
  for (int c = 0; c < 3; ++c) {
    if (have) {
      w->Add(v(c), decimals);
    } else {
      w->AddEmpty();
    }
  }
}

std::vector<std::string> Columns(const IntersectResult& r, bool with_id = false) {
  std::vector<std::string> cols = {"t_s"};
  if (with_id) cols.push_back("id");
  // The SPEC.md §7 columns (formats/trajectory.h, which rk-export reads), then rk-intersect's own.
  const std::vector<std::string>& spec = formats::TrajectoryColumns();
  cols.insert(cols.end(), spec.begin(), spec.end());
  for (const char* c : {"rho_en", "rho_eu", "rho_nu", "intersection_angle_deg", "gdop", "n_rejected"}) cols.push_back(c);
  if (r.smoothed) {
    for (const char* c : {"ve_mps", "vn_mps", "vu_mps", "sigma_ve_mps", "sigma_vn_mps", "sigma_vu_mps", "ae_mps2",
                          "an_mps2", "au_mps2", "sigma_ae_mps2", "sigma_an_mps2", "sigma_au_mps2"}) {
      cols.push_back(c);
    }
  }
  for (std::size_t s = 0; s < r.names.size(); ++s) {
    cols.push_back(r.names[s] + "_az_res_arcsec");
    cols.push_back(r.names[s] + "_el_res_arcsec");
    if (r.has_range[s]) cols.push_back(r.names[s] + "_range_res_m");
    cols.push_back(r.names[s] + "_los");
  }
  return cols;
}

void AddSolution(io::CsvWriter* w, const TrajectoryRow& tr) {
  const bool ok = tr.status == RowStatus::kOk;
  const Solution& s = tr.result.solution;
  AddVector(w, ok, s.p, kLengthDecimals);
  w->Add(ok ? tr.wgs84.lat_deg : NAN, kDegDecimals);
  w->Add(ok ? tr.wgs84.lon_deg : NAN, kDegDecimals);
  w->Add(ok ? tr.wgs84.h_m : NAN, kLengthDecimals);
  const Eigen::Vector3d sd = s.P.diagonal().cwiseSqrt();
  AddVector(w, ok, sd, kLengthDecimals);
  w->Add(ok ? std::popcount(tr.result.used) : tr.n_lines);
  w->Add(RowStatusName(tr.status));
  w->Add(ok ? tr.result.rms_residual_arcsec : NAN, kFigureDecimals);
  const Eigen::Vector3d rho(s.P(0, 1) / (sd(0) * sd(1)), s.P(0, 2) / (sd(0) * sd(2)), s.P(1, 2) / (sd(1) * sd(2)));
  AddVector(w, ok, rho, kFigureDecimals);
  w->Add(ok ? tr.result.intersection_angle_deg : NAN, kFigureDecimals);
  w->Add(ok ? tr.result.gdop : NAN, kFigureDecimals);
  w->Add(std::popcount(tr.result.rejected));
}

}  // namespace

namespace {

// Row i of r (after its t_s and id).
void AddRowBody(io::CsvWriter* out, const IntersectResult& r, std::size_t i) {
  io::CsvWriter& w = *out;
  const std::size_t S = r.names.size();
  {
    const TrajectoryRow& tr = r.rows[i];
    AddSolution(&w, tr);
    if (r.smoothed) {
      AddVector(&w, tr.has_kinematics, tr.v, kLengthDecimals);
      AddVector(&w, tr.has_kinematics, tr.sigma_v, kLengthDecimals);
      AddVector(&w, tr.has_kinematics, tr.a, kLengthDecimals);
      AddVector(&w, tr.has_kinematics, tr.sigma_a, kLengthDecimals);
    }
    for (std::size_t s = 0; s < S; ++s) {
      const LineUse u = r.Use(i, s);
      const Eigen::Vector3d& res = r.residual[i * S + s];
      const bool have = u != LineUse::kNone;
      w.Add(have ? res(0) : NAN, 3);
      w.Add(have ? res(1) : NAN, 3);
      if (r.has_range[s]) w.Add(have ? res(2) : NAN, kLengthDecimals);
      w.Add(u == LineUse::kUsed ? "used" : (u == LineUse::kRejected ? "rejected" : ""));
    }
  }
}

}  // namespace

io::CsvWriter TrajectoryCsv(const IntersectResult& r) {
  io::CsvWriter w(Columns(r));
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    w.Add(r.rows[i].t_s, 9);
    AddRowBody(&w, r, i);
    w.EndRow();
  }
  return w;
}

io::CsvWriter TrajectoryCsv(const std::vector<IntersectResult>& by_id) {
  RK_CHECK(!by_id.empty(), "no trajectory");
  io::CsvWriter w(Columns(by_id.front(), true));
  struct Ref {
    double t;
    std::size_t id, row;
  };
  std::vector<Ref> refs;
  for (std::size_t k = 0; k < by_id.size(); ++k)
    for (std::size_t i = 0; i < by_id[k].rows.size(); ++i) refs.push_back({by_id[k].rows[i].t_s, k, i});
  std::stable_sort(refs.begin(), refs.end(), [](const Ref& a, const Ref& b) { return a.t < b.t; });
  for (const Ref& ref : refs) {
    w.Add(ref.t, 9).Add(by_id[ref.id].id);
    AddRowBody(&w, by_id[ref.id], ref.row);
    w.EndRow();
  }
  return w;
}


io::Json IntersectResult::SummaryJson() const {
  std::vector<double> sigma, gdop, angle, rms;
  for (const TrajectoryRow& tr : rows) {
    if (tr.status != RowStatus::kOk) continue;
    sigma.push_back(std::sqrt(tr.result.solution.P.trace()));
    gdop.push_back(tr.result.gdop);
    angle.push_back(tr.result.intersection_angle_deg);
    rms.push_back(tr.result.rms_residual_arcsec);
  }
  return {{"rows_ok", rows_ok},
          {"rows_lost", rows_lost},
          {"rows_invalid", rows_invalid},
          {"rows_with_rejection", rows_with_rejection},
          {"median_sigma_3d_m", NumberOrNull(internal::UpperMedianOrNaN(sigma))},
          {"median_gdop", NumberOrNull(internal::UpperMedianOrNaN(gdop))},
          {"median_intersection_angle_deg", NumberOrNull(internal::UpperMedianOrNaN(angle))},
          {"median_rms_residual_arcsec", NumberOrNull(internal::UpperMedianOrNaN(rms))}};
}

io::RunSummary IntersectResult::Summary() const {
  io::RunSummary out;
  for (const TrajectoryRow& tr : rows) out.CountRows(tr.status);
  if (rows_lost > 0) {
    out.Warn("rows_lost", std::to_string(rows_lost) + " of " + std::to_string(rows.size()) +
                              " rows have fewer than two lines of sight (status lost)");
  }
  std::vector<double> sigma;
  for (const TrajectoryRow& tr : rows)
    if (tr.status == RowStatus::kOk) sigma.push_back(std::sqrt(tr.result.solution.P.trace()));
  if (!sigma.empty()) {
    out.AddFigure("median 3-D 1σ", internal::UpperMedianOrNaN(sigma), "m",
                  std::to_string(rows_ok) + " of " + std::to_string(rows.size()) + " rows");
  }
  out.details = ToJson();
  return out;
}

io::Json IntersectResult::ToJson() const {
  io::Json j;
  j["counts"] = {{"rows", rows.size()}, {"ok", rows_ok}, {"lost", rows_lost}, {"invalid", rows_invalid},
                 {"with_rejection", rows_with_rejection}};
  io::Json st = io::Json::object();
  for (std::size_t s = 0; s < names.size(); ++s) {
    const StationCounts& c = stations[s];
    const double n = static_cast<double>(c.rows_used);
    const Eigen::Vector3d enu = s < station_enu.size() ? station_enu[s] : Eigen::Vector3d::Constant(NAN);
    st[names[s]] = {{"enu_m", {NumberOrNull(enu.x()), NumberOrNull(enu.y()), NumberOrNull(enu.z())}},
                    {"rows_contributed", c.rows_contributed},
                    {"rows_used", c.rows_used},
                    {"rows_rejected", c.rows_rejected},
                    {"rms_az_residual_arcsec", NumberOrNull(n > 0 ? std::sqrt(c.sum2_az / n) : NAN)},
                    {"rms_el_residual_arcsec", NumberOrNull(n > 0 ? std::sqrt(c.sum2_el / n) : NAN)},
                    {"rms_range_residual_m",
                     NumberOrNull(c.n_range > 0 ? std::sqrt(c.sum2_range / static_cast<double>(c.n_range)) : NAN)}};
  }
  j["stations"] = st;
  std::vector<double> rho[3];
  for (const TrajectoryRow& tr : rows) {
    if (tr.status != RowStatus::kOk) continue;
    const Eigen::Matrix3d& P = tr.result.solution.P;
    rho[0].push_back(P(0, 1) / std::sqrt(P(0, 0) * P(1, 1)));
    rho[1].push_back(P(0, 2) / std::sqrt(P(0, 0) * P(2, 2)));
    rho[2].push_back(P(1, 2) / std::sqrt(P(1, 1) * P(2, 2)));
  }
  j["correlations"] = {{"median_rho_en", NumberOrNull(internal::UpperMedianOrNaN(rho[0]))},
                       {"median_rho_eu", NumberOrNull(internal::UpperMedianOrNaN(rho[1]))},
                       {"median_rho_nu", NumberOrNull(internal::UpperMedianOrNaN(rho[2]))}};
  if (smoothed) {
    filter::Series s;
    s.columns = {"e_m", "n_m", "u_m"};
    s.is_angle = {false, false, false};
    j["smooth"] = singer.ColumnsJson(s, false);
  }
  j["summary"] = SummaryJson();
  return j;
}

}  // namespace rk::intersect
