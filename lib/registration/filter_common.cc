#include "registration/filter_common.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>

#include "geo/angles.h"
#include "io/csv.h"

namespace rk::registration {
namespace {

// Eigenvalue floor of a repaired covariance, relative to its largest eigenvalue.
constexpr double kRepairRelativeFloor = 1e-15;
constexpr int kTimeDecimals = 9;
constexpr int kValueDecimals = 9;

}  // namespace

const io::OptionTable<FilterOptions>& FilterOptions::Table() {
  static const io::OptionTable<FilterOptions> table =
      io::OptionTable<FilterOptions>()
          .Sub(&FilterOptions::noise, MeasurementNoise::Table())
          .Choice("--linearize", &FilterOptions::linearization, {Linearization::kEstimate, Linearization::kMeasured},
                  LinearizationName,
                  "Linearisation point of the measurement model: estimate (current bias estimate) or measured "
                  "(the paper's eqs. 2 and 7: about the measured values)");
  return table;
}

bool FilterOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  for (int i = 0; i < kRadarBiasDim; ++i) {
    if (!(initial_sigma[i] > 0 && std::isfinite(initial_sigma[i]))) {
      if (why) *why = std::string("initial sigma of ") + BiasName(i) + " must be > 0";
      return false;
    }
    if (!(process_sigma[i] >= 0 && std::isfinite(process_sigma[i]))) {
      if (why) *why = std::string("process sigma of ") + BiasName(i) + " must be >= 0";
      return false;
    }
  }
  return true;
}

io::Json FilterOptions::ToJson() const {
  io::Json j = Table().ToJson(*this);
  for (int i = 0; i < kRadarBiasDim; ++i) {
    j["initial_sigma"][BiasColumnSuffix(i)] = initial_sigma[i] * BiasToFileUnit(i);
    j["process_sigma_per_step"][BiasColumnSuffix(i)] = process_sigma[i] * BiasToFileUnit(i);
  }
  return j;
}

BiasMatrix InitialCovariance(const FilterOptions& opt) {
  BiasVector v;
  v << opt.initial_sigma.cwiseAbs2(), opt.initial_sigma.cwiseAbs2();
  return v.asDiagonal();
}

BiasMatrix ProcessCovariance(const FilterOptions& opt) {
  BiasVector v;
  v << opt.process_sigma.cwiseAbs2(), opt.process_sigma.cwiseAbs2();
  return v.asDiagonal();
}

io::Json FilterCounters::ToJson() const {
  io::Json j;
  j["steps"] = steps;
  j["steps_updated"] = steps_updated;
  j["steps_predicted"] = steps_predicted;
  j["pairs_evaluated"] = pairs_evaluated;
  j["updates"] = updates;
  j["innovation_not_pd"] = innovation_not_pd;
  j["covariance_repairs"] = covariance_repairs;
  return j;
}

bool SymmetrizeAndRepair(BiasMatrix* P) {
  *P = 0.5 * (*P + P->transpose()).eval();
  Eigen::LLT<BiasMatrix> llt(*P);
  if (llt.info() == Eigen::Success) return false;
  Eigen::SelfAdjointEigenSolver<BiasMatrix> es(*P);
  BiasVector ev = es.eigenvalues();
  const double floor = std::max(ev.maxCoeff(), 1e-300) * kRepairRelativeFloor;
  for (int i = 0; i < kBiasDim; ++i) ev[i] = std::max(ev[i], floor);
  *P = es.eigenvectors() * ev.asDiagonal() * es.eigenvectors().transpose();
  *P = 0.5 * (*P + P->transpose()).eval();
  return true;
}

namespace {

// UpdateWithPair for a pair with a 2-D plot: the same Joseph-form update on the reduced pair (dimension < 3).
bool UpdateReduced(const PlotLinearization& a, const PlotLinearization& b, BiasVector* m, BiasMatrix* P,
                   FilterCounters* counters, double* d2, double* log_q, int* dim) {
  const ReducedPair rp = ReducePair(a, b, *m);
  if (dim) *dim = rp.dim;
  const Eigen::Matrix<double, kBiasDim, Eigen::Dynamic, 0, kBiasDim, 3> PHt = *P * rp.H.transpose();
  MatX3 S = rp.H * PHt + rp.R;
  S = 0.5 * (S + S.transpose()).eval();
  const Eigen::LLT<MatX3> llt(S);
  if (llt.info() != Eigen::Success) {
    ++counters->innovation_not_pd;
    return false;
  }
  const Eigen::Matrix<double, kBiasDim, Eigen::Dynamic, 0, kBiasDim, 3> K = llt.solve(PHt.transpose()).transpose();
  const VecX3 w = llt.matrixL().solve(rp.nu);
  if (d2) *d2 = w.squaredNorm();
  if (log_q) {
    const MatX3 L = llt.matrixL();
    *log_q = -0.5 * w.squaredNorm() - 0.5 * rp.dim * kLog2Pi - L.diagonal().array().log().sum();
  }
  *m += K * rp.nu;
  const BiasMatrix A = BiasMatrix::Identity() - K * rp.H;
  *P = A * *P * A.transpose() + K * rp.R * K.transpose();
  if (SymmetrizeAndRepair(P)) ++counters->covariance_repairs;
  ++counters->updates;
  return true;
}

}  // namespace

bool UpdateWithPair(const PlotLinearization& a, const PlotLinearization& b, BiasVector* m, BiasMatrix* P,
                    FilterCounters* counters, double* d2, double* log_q, int* dim) {
  ++counters->pairs_evaluated;
  if (!a.has_el || !b.has_el) return UpdateReduced(a, b, m, P, counters, d2, log_q, dim);
  if (dim) *dim = 3;
  const Vec3 nu = b.PointAt(m->tail<kRadarBiasDim>()) - a.PointAt(m->head<kRadarBiasDim>());
  Eigen::Matrix<double, 3, kBiasDim> H;
  H.leftCols<kRadarBiasDim>() = a.J;
  H.rightCols<kRadarBiasDim>() = -b.J;
  const Mat3 R = a.noise_cov + b.noise_cov;
  const Eigen::Matrix<double, kBiasDim, 3> PHt = *P * H.transpose();
  Mat3 S = H * PHt + R;
  S = 0.5 * (S + S.transpose()).eval();
  Eigen::LLT<Mat3> llt(S);
  if (llt.info() != Eigen::Success) {
    ++counters->innovation_not_pd;
    return false;
  }
  const Eigen::Matrix<double, kBiasDim, 3> K = llt.solve(PHt.transpose()).transpose();
  const Vec3 w = llt.matrixL().solve(nu);
  if (d2) *d2 = w.squaredNorm();
  if (log_q) {
    const Mat3 L = llt.matrixL();
    *log_q = -0.5 * w.squaredNorm() - 0.5 * 3 * kLog2Pi - std::log(L(0, 0) * L(1, 1) * L(2, 2));
  }
  *m += K * nu;
  const BiasMatrix A = BiasMatrix::Identity() - K * H;
  *P = A * *P * A.transpose() + K * R * K.transpose();
  if (SymmetrizeAndRepair(P)) ++counters->covariance_repairs;
  ++counters->updates;
  return true;
}

BiasMask UnobservableBiases(const RegistrationInput& input, const BiasMatrix& P, const RadarBias& prior_sigma) {
  BiasMask out{};
  for (int r = 0; r < 2; ++r) {
    if (!input.two_d[r]) continue;
    out[r][kBiasEl] = true;
    for (int i : {kBiasPitch, kBiasRoll}) {
      const double var = P(r * kRadarBiasDim + i, r * kRadarBiasDim + i);
      out[r][i] = !(std::isfinite(var) && std::sqrt(std::max(0.0, var)) <= kUnresolvedSigmaRatio * prior_sigma[i]);
    }
  }
  return out;
}

io::CsvWriter BiasesCsv(const RegistrationInput& input, const RegistrationResult& result, bool sigmas) {
  std::vector<std::string> cols{"t_s"};
  for (int r = 0; r < 2; ++r) {
    for (int i = 0; i < kRadarBiasDim; ++i) cols.push_back(input.radars[r] + "_" + BiasColumnSuffix(i));
  }
  cols.push_back("status");
  if (sigmas) {
    for (int r = 0; r < 2; ++r) {
      for (int i = 0; i < kRadarBiasDim; ++i) cols.push_back(input.radars[r] + "_" + BiasSigmaColumnSuffix(i));
    }
  }
  io::CsvWriter csv(cols);
  for (const StepEstimate& s : result.steps) {
    csv.Add(s.t_s, kTimeDecimals);
    const auto hidden = [&](int j) { return result.unobservable[j / kRadarBiasDim][j % kRadarBiasDim]; };
    for (int j = 0; j < kBiasDim; ++j) {
      if (hidden(j)) {
        csv.AddEmpty();
      } else {
        csv.Add(s.x[j] * BiasToFileUnit(j % kRadarBiasDim), kValueDecimals);
      }
    }
    csv.Add(RowStatusName(s.status));
    if (sigmas) {
      for (int j = 0; j < kBiasDim; ++j) {
        if (hidden(j)) {
          csv.AddEmpty();
        } else {
          csv.Add(s.sigma[j] * BiasToFileUnit(j % kRadarBiasDim), kValueDecimals);
        }
      }
    }
    csv.EndRow();
  }
  return csv;
}

io::Json EstimateJson(const RegistrationInput& input, const BiasVector& x, const BiasMatrix& P,
                      const BiasMask& unobservable) {
  io::Json j;
  io::Json corr = io::Json::array();
  std::vector<std::string> names;
  const auto hidden = [&](int k) { return unobservable[k / kRadarBiasDim][k % kRadarBiasDim]; };
  for (int r = 0; r < 2; ++r) {
    for (int i = 0; i < kRadarBiasDim; ++i) {
      const int k = r * kRadarBiasDim + i;
      const double u = BiasToFileUnit(i);
      if (hidden(k)) {
        j["estimate"][input.radars[r]][BiasColumnSuffix(i)] = nullptr;
        j["sigma"][input.radars[r]][BiasColumnSuffix(i)] = nullptr;
      } else {
        j["estimate"][input.radars[r]][BiasColumnSuffix(i)] = x[k] * u;
        j["sigma"][input.radars[r]][BiasColumnSuffix(i)] = std::sqrt(std::max(0.0, P(k, k))) * u;
      }
      names.push_back(input.radars[r] + "_" + BiasColumnSuffix(i));
    }
  }
  for (int a = 0; a < kBiasDim; ++a) {
    io::Json row = io::Json::array();
    for (int b = 0; b < kBiasDim; ++b) {
      const double d = std::sqrt(std::max(0.0, P(a, a)) * std::max(0.0, P(b, b)));
      if (hidden(a) || hidden(b)) {
        row.push_back(nullptr);
      } else {
        row.push_back(d > 0 ? P(a, b) / d : 0.0);
      }
    }
    corr.push_back(row);
  }
  j["correlation"] = {{"order", names}, {"matrix", corr}};
  return j;
}

namespace {

// Σ of every member named `key` in `j`, at any depth (the methods keep their counters at different places).
std::int64_t SumMembers(const io::Json& j, const std::string& key) {
  std::int64_t n = 0;
  if (!j.is_object()) return 0;
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it.key() == key && it.value().is_number_integer()) n += it.value().get<std::int64_t>();
    n += SumMembers(it.value(), key);
  }
  return n;
}

}  // namespace

io::RunSummary RegistrationResult::Summary(const RegistrationInput& input) const {
  io::RunSummary out;
  out.rows_by_status.emplace();
  for (const StepEstimate& s : steps) out.CountRows(s.status);
  for (int r = 0; r < 2; ++r) {
    if (input.summary.nav_unfolded_rows[r] > 0) {
      out.Warn("nav_pitch_folded",
               "nav of radar '" + input.radars[r] + "': " + std::to_string(input.summary.nav_unfolded_rows[r]) +
                   " rows had the pitch folded into [-90, 90] (yaw and roll +180); read as the continuous angles");
    }
  }
  for (int r = 0; r < 2; ++r) {
    const std::string radar = "radar '" + input.radars[r] + "'";
    if (input.two_d[r]) {
      std::string msg = radar + " is 2-D (no el_deg): its el bias is unobservable (no elevation is measured, so a "
                                "plot's elevation is unknown and its bias cannot be told from it)";
      const bool pitch = unobservable[r][kBiasPitch], roll = unobservable[r][kBiasRoll];
      if (pitch || roll) {
        msg += std::string(", and its ") + (pitch && roll ? "pitch and roll biases are" : pitch ? "pitch bias is" : "roll bias is") +
               " unobservable in this trial (a 2-D plot moves with them only through the target's elevation in the "
               "radar frame and the platform's tilt; the data left their 1-sigma above half the prior's)";
      }
      out.Warn("radar_2d_unobservable", msg + "; left empty");
    } else if (input.summary.plots_without_el[r] > 0) {
      out.Warn("radar_plots_without_el",
               radar + ": " + std::to_string(input.summary.plots_without_el[r]) + " of " +
                   std::to_string(input.summary.plots[r]) +
                   " plots have no el_deg: used as 2-D plots (elevation unknown); its el bias comes from the others");
    }
  }
  const std::int64_t repairs = SumMembers(stats, "covariance_repairs");
  if (repairs > 0) out.Flag("covariance_repaired", std::to_string(repairs) + " covariance repair(s)");
  if (stats.contains("termination") && stats["termination"].is_string()) {
    const std::string t = stats["termination"].get<std::string>();
    out.termination = t == "CONVERGENCE" ? "converged" : t;
    if (t != "CONVERGENCE") out.Flag("not_converged", "the batch solve ended with " + t + ", not convergence");
  }
  io::Json details = ToJson(input);
  for (int r = 0; r < 2; ++r) {
    const io::Json& est = details["estimate"][input.radars[r]];
    const io::Json& sig = details["sigma"][input.radars[r]];
    if (!est.contains("range_m") || !est["range_m"].is_number()) continue;
    const bool has_sigma = sig.is_object() && sig.contains("range_m") && sig["range_m"].is_number();
    char note[64] = "";
    if (has_sigma) std::snprintf(note, sizeof note, "1σ %.3g m", sig["range_m"].get<double>());
    out.AddFigure("radar " + input.radars[r] + " range bias", est["range_m"].get<double>(), "m", note);
  }
  out.details = std::move(details);
  return out;
}

io::Json RegistrationResult::ToJson(const RegistrationInput& input) const {
  io::Json j;
  j["radars"] = {input.radars[0], input.radars[1]};
  j["input"] = input.summary.ToJson(input.radars);
  const io::Json est = EstimateJson(input, x, P, unobservable);
  for (auto it = est.begin(); it != est.end(); ++it) j[it.key()] = it.value();
  j["stats"] = stats;
  if (j["stats"].contains("options")) {
    j["options"] = j["stats"]["options"];
    j["stats"].erase("options");
  }
  j["summary"] = {{"estimate", est["estimate"]}, {"sigma", est["sigma"]}};
  return j;
}

}  // namespace rk::registration
