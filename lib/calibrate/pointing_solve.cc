// Pointing calibration by Ceres; model, priors and covariance in pointing_solve.h.
#include "calibrate/pointing_solve.h"

#include <ceres/ceres.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>

#include "calibrate/pointing_cost.h"
#include "geo/angles.h"
#include "geo/line_of_sight.h"
#include "io/error.h"

namespace rk::calibrate {
namespace {

constexpr double kMaxInitElevationRad = 70.0 * geo::kPi / 180.0;  // azimuth too ill-defined above this
constexpr double kTauConvergedS = 1e-6;   // τ moved less than this: no re-evaluation of the turret log
constexpr double kChi2WarnHigh = 2.0;     // χ²/dof above this: the stated σ are too small for the data
constexpr double kSmallEigenvalue = 1e-4; // of the correlation matrix: a combination poorly determined
// Ceres stops when the cost changes by less than 1e-10 relatively (≪ 1/N of χ² for any session) or the
// parameters by less than 1e-10 relatively (0.02 mas of az_offset).
constexpr double kFunctionTolerance = 1e-10, kParameterTolerance = 1e-10;
// More than this fraction of the observations above kOutlierChi2 is not a few outliers but a model that does
// not fit (an unestimated focal error or latency, a wrong epoch): nothing is rejected and a warning says so.
constexpr double kMaxOutlierFraction = 0.2;

// A prior residual a/σ on a two-component nuisance block.
struct PriorCost {
  Eigen::Vector2d inv_sigma;
  template <typename T>
  bool operator()(const T* a, T* r) const {
    r[0] = a[0] * T(inv_sigma.x());
    r[1] = a[1] * T(inv_sigma.y());
    return true;
  }
};

// The state of one solve: parameters, nuisance blocks and which observations take part.
struct Problem {
  const PointingObservations* obs = nullptr;
  Intrinsics in;
  std::array<double, kNumPointingParams> x{};
  std::vector<Eigen::Vector2d> c, t;      // cluster and target nuisance values
  std::vector<char> active;               // per observation
  std::vector<std::unique_ptr<ceres::CostFunction>> costs;  // per observation (owned here)
};

ceres::CostFunction* MakeCost(const PointingObservation& o, const Intrinsics& in, double tau0) {
  return new ceres::AutoDiffCostFunction<PointingPixelCost, 2, kNumPointingParams, 2, 2>(
      new PointingPixelCost(o, in, tau0));
}

bool HasPrior(double sigma) { return sigma > 0.0; }

// One robust Ceres solve of the active observations; returns iterations and fills *termination.
int RunCeres(const EstimateSet& est, int max_iterations, Problem* p, std::string* termination) {
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.manifold_ownership = ceres::TAKE_OWNERSHIP;
  std::vector<std::unique_ptr<ceres::CostFunction>> priors;  // outlive the problem (it does not own costs)
  ceres::Problem problem(po);
  std::vector<Eigen::Vector2d> fixed(p->obs->obs.size(), Eigen::Vector2d::Zero());
  std::vector<char> cluster_used(p->c.size(), 0), target_used(p->t.size(), 0);
  for (std::size_t i = 0; i < p->obs->obs.size(); ++i) {
    if (!p->active[i]) continue;
    const PointingObservation& o = p->obs->obs[i];
    double* cb = p->c[static_cast<std::size_t>(o.cluster)].data();
    double* tb = HasPrior(p->obs->target_sigma_rad[static_cast<std::size_t>(o.target)])
                     ? p->t[static_cast<std::size_t>(o.target)].data()
                     : fixed[i].data();
    problem.AddResidualBlock(p->costs[i].get(), new ceres::HuberLoss(kHuberScale), p->x.data(), cb, tb);
    if (tb == fixed[i].data()) problem.SetParameterBlockConstant(tb);
    cluster_used[static_cast<std::size_t>(o.cluster)] = 1;
    target_used[static_cast<std::size_t>(o.target)] = 1;
  }
  for (std::size_t k = 0; k < p->c.size(); ++k) {
    if (!cluster_used[k]) continue;
    const Eigen::Vector2d s = p->obs->cluster_sigma_rad[k];
    if (s.minCoeff() > 0.0) {
      priors.emplace_back(new ceres::AutoDiffCostFunction<PriorCost, 2, 2>(new PriorCost{s.cwiseInverse()}));
      problem.AddResidualBlock(priors.back().get(), nullptr, p->c[k].data());
    } else {
      problem.SetParameterBlockConstant(p->c[k].data());
    }
  }
  for (std::size_t j = 0; j < p->t.size(); ++j) {
    const double s = p->obs->target_sigma_rad[j];
    if (!target_used[j] || !HasPrior(s)) continue;
    priors.emplace_back(
        new ceres::AutoDiffCostFunction<PriorCost, 2, 2>(new PriorCost{Eigen::Vector2d::Constant(1.0 / s)}));
    problem.AddResidualBlock(priors.back().get(), nullptr, p->t[j].data());
  }
  std::vector<int> constant;
  for (int k = 0; k < kNumPointingParams; ++k) {
    if (!est[static_cast<std::size_t>(k)]) constant.push_back(k);
  }
  if (!constant.empty()) problem.SetManifold(p->x.data(), new ceres::SubsetManifold(kNumPointingParams, constant));
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  so.max_num_iterations = max_iterations;
  so.function_tolerance = kFunctionTolerance;
  so.parameter_tolerance = kParameterTolerance;
  so.num_threads = 1;
  std::string why;
  if (!so.IsValid(&why)) so.linear_solver_type = ceres::DENSE_QR;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  *termination = summary.message;
  if (!summary.IsSolutionUsable()) throw ProcessingError("pointing solve failed: " + summary.message);
  return static_cast<int>(summary.iterations.size());
}

// Column layout of the full Jacobian: estimated x, then cluster pairs, then target pairs with a prior.
struct Columns {
  std::vector<int> x_col;                // per parameter: column or -1
  std::vector<int> cluster_col, target_col;
  int n = 0;
  Columns(const Problem& p, const EstimateSet& est) : x_col(kNumPointingParams, -1) {
    for (int k = 0; k < kNumPointingParams; ++k) {
      if (est[static_cast<std::size_t>(k)]) x_col[static_cast<std::size_t>(k)] = n++;
    }
    cluster_col.assign(p.c.size(), -1);
    target_col.assign(p.t.size(), -1);
    for (std::size_t i = 0; i < p.obs->obs.size(); ++i) {
      if (!p.active[i]) continue;
      const PointingObservation& o = p.obs->obs[i];
      int& cc = cluster_col[static_cast<std::size_t>(o.cluster)];
      if (cc < 0 && p.obs->cluster_sigma_rad[static_cast<std::size_t>(o.cluster)].minCoeff() > 0.0) cc = (n += 2) - 2;
      int& tc = target_col[static_cast<std::size_t>(o.target)];
      if (tc < 0 && HasPrior(p.obs->target_sigma_rad[static_cast<std::size_t>(o.target)])) tc = (n += 2) - 2;
    }
  }
};

// Residual and Jacobians of observation i at the current state (no robust loss).
struct Linearised {
  Eigen::Vector2d r;
  Eigen::Matrix<double, 2, kNumPointingParams, Eigen::RowMajor> jx;
  Eigen::Matrix<double, 2, 2, Eigen::RowMajor> jc, jt;
  bool ok = false;
};
Linearised Linearise(const Problem& p, std::size_t i, bool nuisance_zero) {
  const PointingObservation& o = p.obs->obs[i];
  Eigen::Vector2d zero = Eigen::Vector2d::Zero();
  const double* params[3] = {p.x.data(), nuisance_zero ? zero.data() : p.c[static_cast<std::size_t>(o.cluster)].data(),
                             nuisance_zero ? zero.data() : p.t[static_cast<std::size_t>(o.target)].data()};
  Linearised l;
  double* jac[3] = {l.jx.data(), l.jc.data(), l.jt.data()};
  l.ok = p.costs[i]->Evaluate(params, l.r.data(), jac);
  return l;
}

// Covariance of the estimated x: the x-block of (JᵀJ)⁻¹ over pixel and prior rows (sparse Cholesky).
Eigen::MatrixXd Covariance(const Problem& p, const EstimateSet& est) {
  const Columns cols(p, est);
  std::vector<Eigen::Triplet<double>> trip;
  auto add_block = [&](const Eigen::MatrixXd& jj, const std::vector<int>& c) {
    for (int a = 0; a < jj.rows(); ++a) {
      for (int b = 0; b < jj.cols(); ++b) {
        if (c[static_cast<std::size_t>(a)] >= 0 && c[static_cast<std::size_t>(b)] >= 0 && jj(a, b) != 0.0) {
          trip.emplace_back(c[static_cast<std::size_t>(a)], c[static_cast<std::size_t>(b)], jj(a, b));
        }
      }
    }
  };
  for (std::size_t i = 0; i < p.obs->obs.size(); ++i) {
    if (!p.active[i]) continue;
    const PointingObservation& o = p.obs->obs[i];
    const Linearised l = Linearise(p, i, false);
    Eigen::Matrix<double, 2, kNumPointingParams + 4> j;
    j << l.jx, l.jc, l.jt;
    std::vector<int> c(cols.x_col);
    const int cc = cols.cluster_col[static_cast<std::size_t>(o.cluster)];
    const int tc = cols.target_col[static_cast<std::size_t>(o.target)];
    for (int k = 0; k < 2; ++k) c.push_back(cc >= 0 ? cc + k : -1);
    for (int k = 0; k < 2; ++k) c.push_back(tc >= 0 ? tc + k : -1);
    add_block(j.transpose() * j, c);
  }
  for (std::size_t k = 0; k < cols.cluster_col.size(); ++k) {
    if (cols.cluster_col[k] < 0) continue;
    for (int a = 0; a < 2; ++a) {
      const double s = p.obs->cluster_sigma_rad[k][a];
      trip.emplace_back(cols.cluster_col[k] + a, cols.cluster_col[k] + a, 1.0 / (s * s));
    }
  }
  for (std::size_t j = 0; j < cols.target_col.size(); ++j) {
    if (cols.target_col[j] < 0) continue;
    const double s = p.obs->target_sigma_rad[j];
    for (int a = 0; a < 2; ++a) trip.emplace_back(cols.target_col[j] + a, cols.target_col[j] + a, 1.0 / (s * s));
  }
  Eigen::SparseMatrix<double> H(cols.n, cols.n);
  H.setFromTriplets(trip.begin(), trip.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(H);
  const int ne = static_cast<int>(std::count(est.begin(), est.end(), true));
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(cols.n, ne);
  for (int k = 0; k < ne; ++k) rhs(k, k) = 1.0;
  const Eigen::MatrixXd sol = ldlt.solve(rhs);
  if (ldlt.info() != Eigen::Success || !sol.allFinite() || (ldlt.vectorD().array() <= 0.0).any()) {
    throw ProcessingError("the observations do not determine every estimated parameter (singular information matrix); "
                          "estimate fewer terms or add targets at other azimuths and elevations");
  }
  Eigen::MatrixXd cov = sol.topRows(ne);
  return 0.5 * (cov + cov.transpose());
}

// Marginal residual (nuisance zero) of each observation and its χ² against S = σ-whitened I + J_c Q J_cᵀ + …
void Residuals(const Problem& p, PointingSolution* s) {
  s->residuals.clear();
  for (std::size_t i = 0; i < p.obs->obs.size(); ++i) {
    const PointingObservation& o = p.obs->obs[i];
    const Linearised l = Linearise(p, i, true);
    Eigen::Matrix2d S = Eigen::Matrix2d::Identity();
    const Eigen::Vector2d qc = p.obs->cluster_sigma_rad[static_cast<std::size_t>(o.cluster)].cwiseAbs2();
    S += l.jc * qc.asDiagonal() * l.jc.transpose();
    const double st = p.obs->target_sigma_rad[static_cast<std::size_t>(o.target)];
    S += st * st * l.jt * l.jt.transpose();
    ObservationResidual r;
    r.row = o.row;
    r.id = p.obs->target_ids[static_cast<std::size_t>(o.target)];
    const geo::AzEl d = geo::AzElFromEnu(o.dir_enu);
    r.target_az_rad = d.az_rad;
    r.target_el_rad = d.el_rad;
    r.residual_px = l.r.cwiseProduct(o.sigma_px);
    r.chi2 = l.ok ? l.r.dot(S.ldlt().solve(l.r)) : std::numeric_limits<double>::infinity();
    r.rejected = !p.active[i];
    s->residuals.push_back(r);
  }
}

std::string PointingFmt(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace

namespace {

// Warnings in words for pairs and combinations of parameters the observations do not separate.
std::vector<std::string> SeparabilityWarnings(const PointingSolution& s) {
  std::vector<std::string> out;
  const int n = static_cast<int>(s.estimated_params.size());
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      const double rho = s.correlation(a, b);
      if (std::abs(rho) <= kSeparabilityCorrelation) continue;
      out.push_back(std::string(PointingParamName(s.estimated_params[static_cast<std::size_t>(a)])) + " and " +
                    PointingParamName(s.estimated_params[static_cast<std::size_t>(b)]) +
                    " are not separated by these observations (correlation " + PointingFmt(rho, 3) +
                    "): their sigmas are large and their sum or difference is what is known; add targets at other "
                    "elevations and azimuths, or fix one with --estimate");
    }
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(s.correlation);
  for (int k = 0; k < n; ++k) {
    if (eig.eigenvalues()(k) >= kSmallEigenvalue) continue;
    std::string names;
    for (int a = 0; a < n; ++a) {
      if (std::abs(eig.eigenvectors()(a, k)) < 0.3) continue;
      names += (names.empty() ? "" : ", ") + std::string(PointingParamName(s.estimated_params[static_cast<std::size_t>(a)]));
    }
    out.push_back("a combination of " + names + " is poorly determined (normalised information eigenvalue " +
                  PointingFmt(eig.eigenvalues()(k), 6) + "); the sigmas reported for them are as large as the data make them");
  }
  return out;
}

void FillStatistics(const Problem& p, PointingSolution* s) {
  double sum2 = 0.0, chi2 = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < p.obs->obs.size(); ++i) {
    if (!p.active[i]) continue;
    const Linearised l = Linearise(p, i, false);
    chi2 += l.r.squaredNorm();
    sum2 += s->residuals[i].residual_px.squaredNorm();
    n += 2;
  }
  for (std::size_t k = 0; k < p.c.size(); ++k) {
    const Eigen::Vector2d sig = p.obs->cluster_sigma_rad[k];
    if (sig.minCoeff() > 0.0) chi2 += p.c[k].cwiseQuotient(sig).squaredNorm();
  }
  for (std::size_t j = 0; j < p.t.size(); ++j) {
    const double sig = p.obs->target_sigma_rad[j];
    if (sig > 0.0) chi2 += p.t[j].squaredNorm() / (sig * sig);
  }
  s->rms_px = n > 0 ? std::sqrt(sum2 / static_cast<double>(n)) : 0.0;
  const double dof = static_cast<double>(n) - static_cast<double>(s->estimated_params.size());
  s->chi2_per_dof = dof > 0 ? chi2 / dof : 0.0;
}

// Rejects the active observations above kOutlierChi2 and returns how many, unless more than
// kMaxOutlierFraction of them are: then none is rejected and *misfit says how many.
std::size_t RejectOutliers(const PointingSolution& s, Problem* p, std::size_t* misfit) {
  std::size_t n = 0, active = 0;
  for (std::size_t i = 0; i < p->active.size(); ++i) {
    active += p->active[i] ? 1 : 0;
    n += p->active[i] && s.residuals[i].chi2 > kOutlierChi2 ? 1 : 0;
  }
  if (static_cast<double>(n) > kMaxOutlierFraction * static_cast<double>(active)) {
    *misfit = n;
    return 0;
  }
  for (std::size_t i = 0; i < p->active.size(); ++i) {
    if (p->active[i] && s.residuals[i].chi2 > kOutlierChi2) p->active[i] = 0;
  }
  return n;
}

void ResetProblem(const PointingObservations& obs, const camera::CameraModel& cam, Problem* p) {
  p->obs = &obs;
  p->in = cam.ToIntrinsics();
  p->c.assign(obs.cluster_sigma_rad.size(), Eigen::Vector2d::Zero());
  p->t.assign(obs.target_ids.size(), Eigen::Vector2d::Zero());
  p->costs.clear();
  for (const PointingObservation& o : obs.obs) p->costs.emplace_back(MakeCost(o, p->in, obs.tau0_s));
  if (p->active.size() != obs.obs.size()) p->active.assign(obs.obs.size(), 1);
}

}  // namespace

const char* PointingParamName(int param) {
  static const char* const kNames[kNumPointingParams] = {"az_offset",  "tilt_north",  "tilt_east",
                                                         "el_axis_tilt", "mount_yaw", "mount_pitch",
                                                         "mount_roll", "focal",       "time_offset"};
  return param >= 0 && param < kNumPointingParams ? kNames[param] : "?";
}

EstimateSet DefaultEstimate() {
  EstimateSet e{};
  for (int k = kParamAzOffset; k <= kParamMountRoll; ++k) e[static_cast<std::size_t>(k)] = true;
  return e;
}

EstimateSet ParseEstimate(const std::string& list) {
  EstimateSet e{};
  std::stringstream ss(list);
  bool any = false;
  for (std::string name; std::getline(ss, name, ',');) {
    any = true;
    if (name == "az_offset") {
      e[kParamAzOffset] = true;
    } else if (name == "tilt") {
      e[kParamTiltNorth] = e[kParamTiltEast] = true;
    } else if (name == "el_axis_tilt") {
      e[kParamElAxisTilt] = true;
    } else if (name == "mount") {
      e[kParamMountYaw] = e[kParamMountPitch] = e[kParamMountRoll] = true;
    } else if (name == "focal") {
      e[kParamFocal] = true;
    } else if (name == "time_offset") {
      e[kParamTimeOffset] = true;
    } else {
      throw UsageError("--estimate: unknown term '" + name +
                       "' (known: az_offset, tilt, el_axis_tilt, mount, focal, time_offset)");
    }
  }
  if (!any) throw UsageError("--estimate: name at least one term");
  return e;
}

const io::OptionTable<PointingCalibrationOptions>& PointingCalibrationOptions::Table() {
  using O = PointingCalibrationOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Real("--dut1", &O::dut1_s, "s", io::Bounds::Closed(-0.9, 0.9), "UT1 - UTC (s) for the stars")
          .Real("--pressure-hpa", &O::pressure_hpa, "hPa", io::Bounds::Closed(0, 1200),
                "Air pressure at the station (hPa) for the stars' refraction; 0 = no refraction")
          .Real("--temperature-c", &O::temperature_c, "C", io::Bounds::Closed(-90, 60),
                "Air temperature at the station (C) for the stars' refraction")
          .Real("--humidity", &O::humidity, "", io::Bounds::Closed(0, 1), "Relative humidity 0..1")
          .Real("--wavelength-um", &O::wavelength_um, "um", io::Bounds::Closed(0.3, 30),
                "Effective wavelength of the camera (micrometres) for the stars' refraction")
          .Real("--encoder-step-deg", &O::encoder_step_deg, "deg", io::Bounds::AtLeast(0).Finite(),
                "Turret encoder quantum (deg): one reading error (sigma step/sqrt(12)) shared by a dwell")
          .Real("--pixel-sigma-px", &O::pixel_sigma_px, "px", io::Bounds::Positive().Finite(),
                "1-sigma of an image point without sigma_x_px,sigma_y_px (px)")
          .Real("--turret-max-gap", &O::turret_max_gap_s, "s", io::Bounds::Positive(),
                "Longest turret-log interval (s) interpolated across; an observation in a longer gap is an error")
          .Integer("--max-iterations", &O::max_iterations, "", io::Bounds::Closed(1, 10000),
                   "Solver iterations per solve");
  return table;
}

bool PointingCalibrationOptions::Check(std::string* why) const { return Table().Check(*this, why); }
io::Json PointingCalibrationOptions::ToJson() const { return Table().ToJson(*this); }
double PointingCalibrationOptions::encoder_step_rad() const { return geo::DegToRad(encoder_step_deg); }

double InitialAzOffset(const PointingObservations& obs, const camera::CameraModel& cam) {
  std::vector<double> d_all, d_low;
  for (const PointingObservation& o : obs.obs) {
    const geo::AzEl ray = geo::AzElFromEnu(cam.RayEnu(o.px, o.az_log_rad, o.el_log_rad));
    const geo::AzEl tgt = geo::AzElFromEnu(o.dir_enu);
    const double d = geo::WrapPi(tgt.az_rad - ray.az_rad);
    d_all.push_back(d);
    if (tgt.el_rad < kMaxInitElevationRad) d_low.push_back(d);
  }
  const std::vector<double>& d = d_low.empty() ? d_all : d_low;
  double best = 0.0, best_cost = std::numeric_limits<double>::infinity();
  for (double c : d) {  // circular median: the sample minimising the sum of wrapped absolute differences
    double cost = 0.0;
    for (double v : d) cost += std::abs(geo::WrapPi(v - c));
    if (cost < best_cost) best_cost = cost, best = c;
  }
  return best;
}

namespace {

void FillCovariance(const Problem& p, const EstimateSet& est, PointingSolution* s) {
  s->covariance = Covariance(p, est);
  const Eigen::VectorXd sd = s->covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  s->correlation = s->covariance.cwiseQuotient(sd * sd.transpose());
  for (std::size_t a = 0; a < s->estimated_params.size(); ++a) {
    s->sigma[static_cast<std::size_t>(s->estimated_params[a])] = sd(static_cast<int>(a));
    s->correlation(static_cast<int>(a), static_cast<int>(a)) = 1.0;
  }
}

std::size_t ActiveCount(const Problem& p) { return static_cast<std::size_t>(std::count(p.active.begin(), p.active.end(), 1)); }

void RequireEnough(std::size_t n_obs, std::size_t n_params, const std::string& when) {
  if (2 * n_obs > n_params) return;
  throw ProcessingError(std::to_string(n_obs) + " observations" + when + " give " + std::to_string(2 * n_obs) +
                        " residuals, not more than the " + std::to_string(n_params) +
                        " parameters estimated; add observations or estimate fewer terms (--estimate)");
}

}  // namespace

PointingSolution SolvePointing(const ObservationBuilder& build, const camera::CameraModel& cam,
                               const EstimateSet& est, const PointingCalibrationOptions& opt,
                               const std::function<void(std::int64_t)>& progress) {
  PointingSolution s;
  s.estimated = est;
  for (int k = 0; k < kNumPointingParams; ++k) {
    if (est[static_cast<std::size_t>(k)]) s.estimated_params.push_back(k);
  }
  if (s.estimated_params.empty()) throw UsageError("--estimate names no parameter");
  PointingObservations obs = build(cam.time_offset_s);
  RequireEnough(obs.obs.size(), s.estimated_params.size(), "");
  Problem p;
  ResetProblem(obs, cam, &p);
  p.x = {0, 0, 0, 0, cam.mount_yaw_rad, cam.mount_pitch_rad, cam.mount_roll_rad, 0.0, cam.time_offset_s};
  if (est[kParamAzOffset]) p.x[kParamAzOffset] = InitialAzOffset(obs, cam);
  std::size_t misfit = 0;
  std::int64_t solves = 0;
  for (;;) {
    misfit = 0;
    for (int round = 0;; ++round) {
      s.iterations += RunCeres(est, opt.max_iterations, &p, &s.termination);
      if (progress) progress(++solves);
      Residuals(p, &s);
      if (round >= kMaxOutlierRounds || RejectOutliers(s, &p, &misfit) == 0) break;
      RequireEnough(ActiveCount(p), s.estimated_params.size(), " left after rejecting outliers");
    }
    const double tau = p.x[kParamTimeOffset];
    if (!est[kParamTimeOffset] || std::abs(tau - obs.tau0_s) <= kTauConvergedS ||
        s.relinearisations >= kMaxRelinearisations) {
      break;
    }
    obs = build(tau);
    ResetProblem(obs, cam, &p);
    ++s.relinearisations;
  }
  Residuals(p, &s);
  s.x = p.x;
  s.x[kParamAzOffset] = geo::WrapPi(s.x[kParamAzOffset]);
  s.used = ActiveCount(p);
  s.rejected = obs.obs.size() - s.used;
  s.clusters = obs.cluster_sigma_rad.size();
  s.dwells = obs.dwells;
  s.targets = obs.target_ids.size();
  FillCovariance(p, est, &s);
  FillStatistics(p, &s);
  s.warnings = SeparabilityWarnings(s);
  if (misfit > 0) {
    s.warnings.push_back(std::to_string(misfit) + " of " + std::to_string(s.used) +
                         " observations do not fit the model (chi2 > " + PointingFmt(kOutlierChi2, 0) +
                         "), too many to be outliers: none rejected; estimate focal or time_offset, or check the "
                         "epoch, station and target positions");
  }
  if (s.chi2_per_dof > kChi2WarnHigh) {
    s.warnings.push_back("the residuals are " + PointingFmt(std::sqrt(s.chi2_per_dof), 2) +
                         " times larger than the stated errors (chi2/dof " + PointingFmt(s.chi2_per_dof, 2) +
                         "): the sigmas assume the stated pixel and encoder errors; check --pixel-sigma-px, "
                         "--encoder-step-deg and the target positions");
  }
  return s;
}

camera::PointingModel PointingSolution::Model() const {
  camera::PointingModel m;
  m.SetTermsRad({x[kParamAzOffset], x[kParamTiltNorth], x[kParamTiltEast], x[kParamElAxisTilt]});
  for (int k = 0; k < 4; ++k) m.sigma_rad[static_cast<std::size_t>(k)] = sigma[static_cast<std::size_t>(k)];
  return m;
}

camera::CameraModel PointingSolution::Camera(const camera::CameraModel& input) const {
  camera::CameraModel c = input;
  c.mount_yaw_rad = x[kParamMountYaw];
  c.mount_pitch_rad = x[kParamMountPitch];
  c.mount_roll_rad = x[kParamMountRoll];
  c.focal_length_mm = focal_length_mm(input);
  c.time_offset_s = x[kParamTimeOffset];
  io::Json cal = c.calibration.is_object() ? c.calibration : io::Json::object();
  io::Json sig = cal.contains("sigma") && cal["sigma"].is_object() ? cal["sigma"] : io::Json::object();
  if (estimated[kParamMountYaw] || estimated[kParamMountPitch] || estimated[kParamMountRoll]) {
    io::Json mount = io::Json::object();
    const char* keys[3] = {"yaw", "pitch", "roll"};
    for (int k = 0; k < 3; ++k) {
      const auto& sg = sigma[static_cast<std::size_t>(kParamMountYaw + k)];
      if (sg) mount[keys[k]] = geo::RadToDeg(*sg);
    }
    sig["mount_deg"] = mount;
  }
  if (sigma[kParamFocal]) sig["focal_length_mm"] = *sigma[kParamFocal] * input.focal_length_mm;
  if (sigma[kParamTimeOffset]) sig["time_offset_s"] = *sigma[kParamTimeOffset];
  cal["sigma"] = sig;
  cal["pointing_method"] = "rk-calibrate pointing";
  cal["pointing_residual_rms_px"] = rms_px;
  c.calibration = cal;
  return c;
}

}  // namespace rk::calibrate
