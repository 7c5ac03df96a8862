// rk-smooth aukf's products: the output table and the report body (filter/aukf_series.h).
#include <limits>
#include <string>
#include <vector>

#include "filter/aukf_series.h"
#include "filter/smoothed_series.h"

namespace rk::filter {

io::CsvWriter AukfCsv(const Series& series, const AukfResult& result, const AukfOutputOptions& out) {
  const int m = result.m;
  SmoothedColumns columns;
  columns.derivatives = out.derivatives;
  columns.sigma_orders = out.sigmas ? 1 : 0;
  SmoothedSeriesWriter w(series, columns, out.decimals);
  // Empty fields: a column before its first value; its 1σ in the forward pass before its noise is known.
  auto write_row = [&](std::size_t j, const char* kind, const Eigen::MatrixXd& X, const Eigen::MatrixXd& SD,
                       bool forward) {
    const Eigen::Index jc = static_cast<Eigen::Index>(j);
    for (int c = 0; c < m; ++c) {
      const std::size_t k = static_cast<std::size_t>(c);
      if (result.HasValue(j, c)) w.Set(k, X(3 * c, jc), X(3 * c + 1, jc), X(3 * c + 2, jc));
      if (forward ? result.HasSigma(j, c) : result.HasValue(j, c)) w.SetSigma(k, 0, SD(3 * c, jc));
    }
    w.Write(result.t_s[j], kind, result.status[j] == AukfStatus::kOk ? "ok" : "predicted");
  };
  const bool smoothed = result.x_smooth.cols() == static_cast<Eigen::Index>(result.t_s.size());
  for (std::size_t j = 0; j < result.t_s.size(); ++j) {
    write_row(j, result.is_mid[j] ? "prediction" : "estimate", result.x_filter, result.sd_filter, true);
    if (smoothed) write_row(j, "smoothed", result.x_smooth, result.sd_smooth, false);
  }
  return std::move(w.csv());
}

io::Json AukfReportJson(const Series& series, const AukfOptions& options, const AukfResult& result) {
  auto matrix = [](const auto& A) {
    io::Json rows = io::Json::array();
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
      io::Json row = io::Json::array();
      for (Eigen::Index j = 0; j < A.cols(); ++j) row.push_back(A(i, j));
      rows.push_back(row);
    }
    return rows;
  };
  io::Json cols = io::Json::array();
  for (int c = 0; c < result.m; ++c) {
    const std::size_t cu = static_cast<std::size_t>(c);
    const bool angle = series.is_angle[cu];
    const double f = angle ? geo::RadToDeg(1.0) : 1.0;
    io::Json col = {{"name", series.columns[cu]},
                    {"angle", angle},
                    {"meas_sigma", f * result.meas_sigma[cu]},
                    {"q", f * f * result.q[cu]},
                    {"unit", angle ? "deg" : "file unit"}};
    if (cu < result.noise_fit.size() && result.noise_fit[cu].evaluations > 0) {
      const NoiseMlFit& fit = result.noise_fit[cu];
      col["noise_ml"] = {{"used", static_cast<bool>(result.noise_fit_used[cu])},
                         {"nll_per_innovation", fit.nll},
                         {"innovations", fit.innovations},
                         {"evaluations", fit.evaluations},
                         {"on_search_bound", fit.on_bound}};
    }
    cols.push_back(col);
  }
  io::Json j;
  // The table's options (keys from the flags) and what the app or the run decided.
  j["options"] = AukfOptions::Table().ToJson(options);
  j["options"].update(io::Json::object(
      {{"adapt", AdaptModeName(options.adapt.mode)},
       {"memory", options.adapt.memory == AdaptMemory::kWindow ? "window" : "fading"},
       {"r_floor", options.adapt.r_floor},
       {"q_floor", options.adapt.q_floor},
       {"r_ceiling", options.adapt.r_ceiling},
       {"q_ceiling", options.adapt.q_ceiling},
       {"meas_sigma_estimated", result.meas_sigma_estimated},
       {"q_estimated", result.q_estimated},
       {"process_model", "white jerk, Q(tau) = q [[tau^5/20, tau^4/8, tau^3/6], [tau^4/8, tau^3/3, "
                         "tau^2/2], [tau^3/6, tau^2/2, tau]] per column"},
       {"columns", cols}}));
  j["counts"] = {{"samples", result.samples},
                 {"nodes", result.t_s.size()},
                 {"updates", result.updates},
                 {"partial_updates", result.partial_updates},
                 {"skipped_updates", result.skipped_updates},
                 {"adapt_steps", result.adapt_steps},
                 {"adapt_skipped_partial_rows", result.adapt_skipped},
                 {"repairs_q", result.q_repairs},
                 {"repairs_r", result.r_repairs},
                 {"repairs_p", result.p_repairs}};
  // σ and q per column in file units.
  auto noise_json = [&](const std::vector<double>& sigma, const std::vector<double>& q) {
    io::Json sg = io::Json::array(), qq = io::Json::array();
    for (int c = 0; c < result.m; ++c) {
      const double f = series.is_angle[static_cast<std::size_t>(c)] ? geo::RadToDeg(1.0) : 1.0;
      sg.push_back(f * sigma[static_cast<std::size_t>(c)]);
      qq.push_back(f * f * q[static_cast<std::size_t>(c)]);
    }
    return io::Json{{"meas_sigma", sg}, {"q", qq}};
  };
  io::Json refits = io::Json::array();
  for (const auto& rf : result.noise_refits) {
    io::Json e = noise_json(rf.meas_sigma, rf.q);
    e["rows"] = rf.rows;
    e["restarted"] = rf.restarted;
    refits.push_back(e);
  }
  j["noise_refits"] = refits;
  if (!result.smooth_meas_sigma.empty()) j["smooth_noise"] = noise_json(result.smooth_meas_sigma, result.smooth_q);
  j["interval_s"] = result.interval_s;
  j["nis_mean"] = result.NisMean();
  j["nis_mean_per_dof"] = result.nis_dof ? result.nis_sum / static_cast<double>(result.nis_dof) : 0.0;
  // Headline figures (docs/rk-smooth.md "Report"): what rk-run copies into a step's quality record.
  j["summary"] = {{"nis_mean", j["nis_mean"]}, {"nis_mean_per_dof", j["nis_mean_per_dof"]},
                  {"updates", result.updates}, {"skipped_updates", result.skipped_updates}};
  j["final_R"] = matrix(result.final_R);
  j["final_Q"] = matrix(result.final_Q);
  j["final_Q_adapted"] = result.final_Q_adapted;
  j["final_noise_units"] =
      "SI and radians; state order [p, p', p''] per column in --columns order; final_Q is the process noise of "
      "one median interval interval_s";
  return j;
}

}  // namespace rk::filter

namespace rk::filter {

io::RunSummary AukfSummary(const Series& series, const AukfOptions& options, const AukfResult& result) {
  io::RunSummary s;
  const bool smoothed = result.x_smooth.cols() == static_cast<Eigen::Index>(result.t_s.size());
  std::size_t samples = 0, updated = 0;
  for (std::size_t j = 0; j < result.t_s.size(); ++j) {
    const RowStatus st = result.status[j] == AukfStatus::kOk ? RowStatus::kOk : RowStatus::kPredicted;
    s.CountRows(st, smoothed ? 2 : 1);
    if (!result.is_mid[j]) {
      ++samples;
      if (result.status[j] == AukfStatus::kOk) ++updated;
    }
  }
  if (result.skipped_updates > 0) {
    s.Warn("no_update_rows", std::to_string(result.skipped_updates) +
                                 " sample rows without any value: no update, status 'predicted'");
  }
  if (samples > 0) {
    s.AddFigure("sample rows updated", static_cast<double>(updated) / static_cast<double>(samples), "fraction",
                std::to_string(updated) + " of " + std::to_string(samples));
  }
  s.details = AukfReportJson(series, options, result);
  return s;
}

}  // namespace rk::filter
