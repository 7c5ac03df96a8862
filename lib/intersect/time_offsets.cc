// Station clock offsets jointly with the trajectory; the method is described in time_offsets.h.
#include "intersect/time_offsets.h"

#include <ceres/ceres.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "geo/angles.h"
#include "intersect/intersect_common.h"
#include "intersect/solver.h"
#include "intersect/station_frames.h"
#include "io/error.h"

namespace rk::intersect {
namespace {

constexpr double kMinKnotS = 0.1, kMaxKnotS = 1.0;  // the automatic knot interval's bounds
constexpr double kKnotFrames = 4.0;                 // × the slowest station's frame interval
constexpr double kMarginKnots = 3.0;                // the spline reaches this many knots past the rows
constexpr int kMaxReassign = 5;                     // solves after rows change knot span
constexpr double kTolerance = 1e-12;                // Ceres function and parameter tolerances
constexpr double kFrameFractionWarn = 0.5;          // warn when σ exceeds this × the station's frame interval

// Uniform cubic B-spline basis and its derivative in u.
void Basis(double u, double B[4], double dB[4]) {
  const double u2 = u * u, u3 = u2 * u, w = 1.0 - u;
  B[0] = w * w * w / 6.0;
  B[1] = (3.0 * u3 - 6.0 * u2 + 4.0) / 6.0;
  B[2] = (-3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0) / 6.0;
  B[3] = u3 / 6.0;
  dB[0] = -0.5 * w * w;
  dB[1] = 0.5 * (3.0 * u2 - 4.0 * u);
  dB[2] = 0.5 * (-3.0 * u2 + 2.0 * u + 1.0);
  dB[3] = 0.5 * u2;
}

struct Spline {
  double t0 = 0.0, h = 1.0;
  int segments = 1;
  std::vector<Eigen::Vector3d> c;  // segments + 3 control points
  int Segment(double tau) const {
    return std::clamp(static_cast<int>(std::floor((tau - t0) / h)), 0, segments - 1);
  }
  Eigen::Vector3d At(double tau) const {
    const int i = Segment(tau);
    double B[4], dB[4];
    Basis((tau - t0) / h - i, B, dB);
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int m = 0; m < 4; ++m) p += B[m] * c[static_cast<std::size_t>(i + m)];
    return p;
  }
};

struct Observation {
  int target = 0, station = 0;
  double t = 0.0;  // the row's time with the starting offset
  LineObservation o;
};

// One row: its whitened residuals (az, el, range; range 0 without one) as a function of the four control points
// of its knot span and its station's correction δ.
class RowCost final : public ceres::SizedCostFunction<3, 3, 3, 3, 3, 1> {
 public:
  RowCost(const StationFrame& frame, const Observation& obs, const Spline& s, int segment)
      : frame_(frame), obs_(obs), t0_(s.t0), h_(s.h), segment_(segment) {}
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    const double tau = obs_.t + x[4][0];
    const double u = (tau - t0_) / h_ - segment_;
    double B[4], dB[4];
    Basis(u, B, dB);
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
    for (int m = 0; m < 4; ++m) {
      const Eigen::Map<const Eigen::Vector3d> c(x[m]);
      p += B[m] * c;
      v += dB[m] / h_ * c;
    }
    const Prediction pr = Predict(frame_, p);
    Eigen::Map<Eigen::Vector3d> z(residuals);
    z = NormalisedResiduals(obs_.o, pr);
    if (!obs_.o.has_range) z(2) = 0.0;
    if (!z.allFinite()) return false;
    if (!jacobians) return true;
    Eigen::Matrix3d dz = -NormalisedJacobian(obs_.o, pr);  // ∂z/∂p
    if (!obs_.o.has_range) dz.row(2).setZero();
    for (int m = 0; m < 4; ++m) {
      if (!jacobians[m]) continue;
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> jm(jacobians[m]);
      jm = B[m] * dz;
    }
    if (jacobians[4]) {
      Eigen::Map<Eigen::Vector3d> jd(jacobians[4]);
      jd = dz * v;
    }
    return true;
  }

 private:
  const StationFrame& frame_;
  const Observation& obs_;
  const double t0_, h_;
  const int segment_;
};

// The smoothness prior: (c₀ − 2 c₁ + c₂) / (h² σ_a).
class AccelPrior final : public ceres::SizedCostFunction<3, 3, 3, 3> {
 public:
  explicit AccelPrior(double w) : w_(w) {}
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    for (int k = 0; k < 3; ++k) residuals[k] = w_ * (x[0][k] - 2.0 * x[1][k] + x[2][k]);
    if (!jacobians) return true;
    const double coef[3] = {w_, -2.0 * w_, w_};
    for (int m = 0; m < 3; ++m) {
      if (!jacobians[m]) continue;
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> jm(jacobians[m]);
      jm = coef[m] * Eigen::Matrix3d::Identity();
    }
    return true;
  }

 private:
  const double w_;
};

class CorrectionPrior final : public ceres::SizedCostFunction<1, 1> {
 public:
  explicit CorrectionPrior(double sigma) : w_(1.0 / sigma) {}
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    residuals[0] = w_ * x[0][0];
    if (jacobians && jacobians[0]) jacobians[0][0] = w_;
    return true;
  }

 private:
  const double w_;
};

// The angle residuals (arcsec: az·cos el, el) of every observation at the splines and corrections: RMS.
double RmsArcsec(const std::vector<Observation>& obs, const std::vector<Spline>& splines,
                 const std::vector<StationFrame>& frames, const std::vector<double>& delta) {
  double s2 = 0.0;
  for (const Observation& ob : obs) {
    const Prediction pr = Predict(frames[static_cast<std::size_t>(ob.station)],
                                  splines[static_cast<std::size_t>(ob.target)].At(ob.t + delta[static_cast<std::size_t>(ob.station)]));
    const double da = geo::WrapPi(ob.o.az_rad - pr.az) * std::cos(pr.el), de = ob.o.el_rad - pr.el;
    s2 += da * da + de * de;
  }
  return obs.empty() ? 0.0 : std::sqrt(s2 / (2.0 * static_cast<double>(obs.size()))) * geo::kArcsecPerRad;
}

// The starting path of a target: its rows' times, intersected (SolveRow) where two stations see it, and the
// control points from it (c_j ≈ p(t0 + (j − 1) h) for a cubic B-spline), linearly interpolated between.
bool StartSpline(const OffsetTarget& target, const std::vector<StationFrame>& frames, double h, Spline* s) {
  std::vector<double> times;
  for (const StationTrack* tr : target.track) {
    for (std::size_t k = 0; k < tr->usable_rows(); ++k) times.push_back(tr->usable_time(k));
  }
  if (times.empty()) return false;
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  std::vector<double> pt;
  std::vector<Eigen::Vector3d> pp;
  std::vector<LineObservation> obs(target.track.size());
  for (double t : times) {
    int n = 0;
    for (std::size_t k = 0; k < target.track.size(); ++k) {
      if (target.track[k]->At(t, &obs[static_cast<std::size_t>(n)])) {
        obs[static_cast<std::size_t>(n++)].station = target.station[k];
      }
    }
    if (n < 2) continue;
    const RowResult r = SolveRow(frames, obs.data(), n, SolverOptions{});
    if (r.solution.status != SolveStatus::kOk) continue;
    pt.push_back(t);
    pp.push_back(r.solution.p);
  }
  if (pt.size() < 2) return false;
  s->h = h;
  s->t0 = times.front() - kMarginKnots * h;
  s->segments = static_cast<int>(std::ceil((times.back() + kMarginKnots * h - s->t0) / h));
  s->c.resize(static_cast<std::size_t>(s->segments + 3));
  for (std::size_t j = 0; j < s->c.size(); ++j) {
    const double tj = s->t0 + (static_cast<double>(j) - 1.0) * h;
    const auto it = std::lower_bound(pt.begin(), pt.end(), tj);
    std::size_t hi = static_cast<std::size_t>(it - pt.begin());
    hi = std::clamp<std::size_t>(hi, 1, pt.size() - 1);
    const double f = (tj - pt[hi - 1]) / (pt[hi] - pt[hi - 1]);
    // Beyond the solved span: the end positions (no extrapolation of a noisy velocity).
    const double fc = std::clamp(f, 0.0, 1.0);
    s->c[j] = (1.0 - fc) * pp[hi - 1] + fc * pp[hi];
  }
  return true;
}

struct Built {
  std::unique_ptr<ceres::Problem> problem;
  std::vector<int> segment;  // per observation
};

Built Build(const std::vector<Observation>& obs, std::vector<Spline>& splines, const std::vector<StationFrame>& frames,
            std::vector<double>& delta, std::size_t reference, bool free_offsets, const TimeOffsetOptions& o) {
  Built b;
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  b.problem = std::make_unique<ceres::Problem>(po);
  b.segment.resize(obs.size());
  for (std::size_t k = 0; k < obs.size(); ++k) {
    const Observation& ob = obs[k];
    Spline& s = splines[static_cast<std::size_t>(ob.target)];
    const int i = s.Segment(ob.t + delta[static_cast<std::size_t>(ob.station)]);
    b.segment[k] = i;
    b.problem->AddResidualBlock(new RowCost(frames[static_cast<std::size_t>(ob.station)], ob, s, i), nullptr,
                                s.c[static_cast<std::size_t>(i)].data(), s.c[static_cast<std::size_t>(i + 1)].data(),
                                s.c[static_cast<std::size_t>(i + 2)].data(), s.c[static_cast<std::size_t>(i + 3)].data(),
                                &delta[static_cast<std::size_t>(ob.station)]);
  }
  for (Spline& s : splines) {
    if (s.c.empty()) continue;
    const double w = 1.0 / (s.h * s.h * o.accel_sigma_mps2);
    for (std::size_t j = 1; j + 1 < s.c.size(); ++j) {
      b.problem->AddResidualBlock(new AccelPrior(w), nullptr, s.c[j - 1].data(), s.c[j].data(), s.c[j + 1].data());
    }
  }
  for (std::size_t st = 0; st < delta.size(); ++st) {
    if (!b.problem->HasParameterBlock(&delta[st])) continue;
    if (st == reference || !free_offsets) {
      b.problem->SetParameterBlockConstant(&delta[st]);
    } else {
      b.problem->AddResidualBlock(new CorrectionPrior(o.correction_sigma_s), nullptr, &delta[st]);
    }
  }
  return b;
}

int Solve(ceres::Problem* problem, const TimeOffsetOptions& o) {
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  std::string why;
  if (!so.IsValid(&why)) so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = o.max_iterations;
  so.function_tolerance = kTolerance;
  so.parameter_tolerance = kTolerance;
  so.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(so, problem, &summary);
  if (!summary.IsSolutionUsable()) throw ProcessingError("clock offset estimation failed: " + summary.message);
  return static_cast<int>(summary.iterations.size());
}

// Solves until no row changed knot span (the corrections move rows' times).
int SolveReassigning(const std::vector<Observation>& obs, std::vector<Spline>& splines,
                     const std::vector<StationFrame>& frames, std::vector<double>& delta, std::size_t reference,
                     bool free_offsets, const TimeOffsetOptions& o, Built* out) {
  int iterations = 0;
  for (int pass = 0; pass < kMaxReassign; ++pass) {
    *out = Build(obs, splines, frames, delta, reference, free_offsets, o);
    iterations += Solve(out->problem.get(), o);
    bool moved = false;
    for (std::size_t k = 0; k < obs.size() && !moved; ++k) {
      const Spline& s = splines[static_cast<std::size_t>(obs[k].target)];
      moved = s.Segment(obs[k].t + delta[static_cast<std::size_t>(obs[k].station)]) != out->segment[k];
    }
    if (!moved) break;
  }
  return iterations;
}

// The corrections' covariance from the whole normal matrix (Jacobian over [free corrections, control points]),
// scaled by χ²/dof when above 1; fills the fit's offsets, σ, σ with the path known and correlation.
void Covariance(ceres::Problem* problem, std::vector<Spline>& splines, std::vector<double>& delta,
                const std::vector<Observation>& obs, const TimeOffsetOptions& options, TimeOffsetFit* fit) {
  const std::size_t S = delta.size();
  std::vector<double*> blocks;
  std::vector<std::size_t> free_station;
  for (std::size_t s = 0; s < S; ++s) {
    if (s != fit->reference && problem->HasParameterBlock(&delta[s]) && fit->rows[s] > 0) {
      blocks.push_back(&delta[s]);
      free_station.push_back(s);
    }
  }
  const std::size_t nd = blocks.size();
  for (Spline& sp : splines) {
    for (Eigen::Vector3d& c : sp.c) blocks.push_back(c.data());
  }
  ceres::Problem::EvaluateOptions eo;
  eo.parameter_blocks = blocks;
  eo.num_threads = 1;
  double cost = 0.0;
  ceres::CRSMatrix crs;
  problem->Evaluate(eo, &cost, nullptr, nullptr, &crs);
  fit->parameters = static_cast<std::size_t>(crs.num_cols);
  const Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor>> J(
      crs.num_rows, crs.num_cols, static_cast<Eigen::Index>(crs.values.size()), crs.rows.data(), crs.cols.data(),
      crs.values.data());
  const Eigen::SparseMatrix<double> N = (J.transpose() * J).pruned();
  // Residual count: two angles per row, a range where it has one (the range residual of a row without one is
  // always 0: not a residual), the priors' pseudo-observations.
  std::size_t zero_rows = 0;
  for (const Observation& ob : obs) zero_rows += ob.o.has_range ? 0 : 1;
  const double dof = std::max(1.0, static_cast<double>(crs.num_rows) - static_cast<double>(crs.num_cols) -
                                       static_cast<double>(zero_rows));
  fit->chi2_per_dof = 2.0 * cost / dof;
  fit->sigma_scale = std::sqrt(std::max(1.0, fit->chi2_per_dof));
  fit->offset_s = fit->start_s;
  fit->sigma_s.assign(S, 0.0);
  fit->sigma_known_s.assign(S, 0.0);
  fit->correlation = Eigen::MatrixXd::Identity(static_cast<Eigen::Index>(S), static_cast<Eigen::Index>(S));
  for (std::size_t s : free_station) fit->offset_s[s] += delta[s];
  if (nd == 0) return;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(N);
  if (ldlt.info() != Eigen::Success) throw ProcessingError("clock offsets: the normal matrix is singular");
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(crs.num_cols, static_cast<Eigen::Index>(nd));
  for (std::size_t k = 0; k < nd; ++k) E(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k)) = 1.0;
  const Eigen::MatrixXd X = ldlt.solve(E);
  Eigen::MatrixXd C = X.topRows(static_cast<Eigen::Index>(nd));
  C = 0.5 * (C + C.transpose()).eval() * fit->sigma_scale * fit->sigma_scale;
  const double prior_info = 1.0 / (options.correction_sigma_s * options.correction_sigma_s);
  for (std::size_t a = 0; a < nd; ++a) {
    const Eigen::Index ia = static_cast<Eigen::Index>(a);
    fit->sigma_s[free_station[a]] = std::sqrt(C(ia, ia));
    // With the path known: the correction's own information, its Jacobian column without the prior.
    fit->sigma_known_s[free_station[a]] = fit->sigma_scale / std::sqrt(std::max(1e-300, N.coeff(ia, ia) - prior_info));
    for (std::size_t b = 0; b < nd; ++b) {
      const Eigen::Index ib = static_cast<Eigen::Index>(b);
      fit->correlation(static_cast<Eigen::Index>(free_station[a]), static_cast<Eigen::Index>(free_station[b])) =
          C(ia, ib) / std::sqrt(C(ia, ia) * C(ib, ib));
    }
  }
}

// Poorly determined offsets, in words.
void Warn(const std::vector<double>& interval, const TimeOffsetOptions& options, TimeOffsetFit* fit) {
  for (std::size_t s = 0; s < fit->sigma_s.size(); ++s) {
    if (s == fit->reference || !(fit->sigma_s[s] > 0.0)) continue;
    const double inflation = fit->sigma_s[s] / fit->sigma_known_s[s];
    char buf[512];
    if (inflation > options.poor_inflation) {
      std::snprintf(buf, sizeof buf,
                    "the clock offset of '%s' is poorly determined: its 1σ %.3g ms is %.0f× what its own rows would "
                    "give with the path known — a time shift and a shift of the path look alike from these "
                    "stations (a straight pass along a line of stations); its σ says so honestly, but the trajectory "
                    "leans on it",
                    fit->names[s].c_str(), 1e3 * fit->sigma_s[s], inflation);
      fit->warnings.push_back(buf);
    } else if (interval[s] > 0.0 && fit->sigma_s[s] > kFrameFractionWarn * interval[s]) {
      std::snprintf(buf, sizeof buf,
                    "the clock offset of '%s' is poorly determined: its 1σ %.3g ms is more than half its frame "
                    "interval (%.3g ms)",
                    fit->names[s].c_str(), 1e3 * fit->sigma_s[s], 1e3 * interval[s]);
      fit->warnings.push_back(buf);
    }
  }
}

}  // namespace

namespace internal {

double RowJacobianMismatch(const StationFrame& frame, const LineObservation& o, double t_s,
                           const Eigen::Vector3d c[4], double delta, double t0, double h) {
  Observation ob;
  ob.t = t_s;
  ob.o = o;
  Spline s;
  s.t0 = t0;
  s.h = h;
  const RowCost cost(frame, ob, s, 0);
  double x[13];
  for (int m = 0; m < 4; ++m)
    for (int k = 0; k < 3; ++k) x[3 * m + k] = c[m](k);
  x[12] = delta;
  auto eval = [&](const double* xv, double* r, double** jac) {
    const double* blocks[5] = {xv, xv + 3, xv + 6, xv + 9, xv + 12};
    return cost.Evaluate(blocks, r, jac);
  };
  double r[3], J[5][9];
  double* jac[5] = {J[0], J[1], J[2], J[3], J[4]};
  if (!eval(x, r, jac)) return std::numeric_limits<double>::infinity();
  double worst = 0.0;
  for (int row = 0; row < 3; ++row) {
    double scale = 0.0, err = 0.0;
    for (int p = 0; p < 13; ++p) {
      const double step = p == 12 ? 1e-6 : 1e-3;  // s, m
      double xp[13], xm[13], rp[3], rm[3];
      std::copy(x, x + 13, xp);
      std::copy(x, x + 13, xm);
      xp[p] += step;
      xm[p] -= step;
      if (!eval(xp, rp, nullptr) || !eval(xm, rm, nullptr)) return std::numeric_limits<double>::infinity();
      const double numeric = (rp[row] - rm[row]) / (2.0 * step);
      const double analytic = p == 12 ? J[4][row] : J[p / 3][3 * row + p % 3];
      scale = std::max(scale, std::abs(numeric));
      err = std::max(err, std::abs(analytic - numeric));
    }
    if (scale > 0.0) worst = std::max(worst, err / scale);
  }
  return worst;
}

}  // namespace internal

TimeOffsetFit EstimateTimeOffsets(const formats::StationsFile& stations, const std::vector<OffsetTarget>& targets,
                                  const TimeOffsetOptions& options) {
  const std::size_t S = stations.stations.size();
  TimeOffsetFit fit;
  fit.reference = stations.TimeReference();
  std::vector<StationFrame> frames;
  for (const formats::StationSpec& s : stations.stations) {
    fit.names.push_back(s.name);
    fit.start_s.push_back(s.time_offset_s);
    frames.push_back(MakeStationFrame(stations.origin, s.position));
  }
  fit.rows.assign(S, 0);
  // The knot interval: a few of the slowest station's frames.
  double slowest = 0.0;
  std::vector<double> interval(S, 0.0);
  for (const OffsetTarget& t : targets) {
    for (std::size_t k = 0; k < t.track.size(); ++k) {
      interval[static_cast<std::size_t>(t.station[k])] = t.track[k]->frame_interval_s();
      slowest = std::max(slowest, t.track[k]->frame_interval_s());
    }
  }
  const double h = options.knot_interval_s > 0.0 ? options.knot_interval_s
                                                  : std::clamp(kKnotFrames * slowest, kMinKnotS, kMaxKnotS);
  fit.knot_interval_s = h;
  // Observations and the starting paths.
  std::vector<Spline> splines(targets.size());
  std::vector<Observation> obs;
  for (std::size_t g = 0; g < targets.size(); ++g) {
    if (targets[g].track.size() < 2 || !StartSpline(targets[g], frames, h, &splines[g])) {
      splines[g].c.clear();
      continue;
    }
    for (std::size_t k = 0; k < targets[g].track.size(); ++k) {
      const StationTrack& tr = *targets[g].track[k];
      for (std::size_t r = 0; r < tr.usable_rows(); ++r) {
        Observation ob;
        ob.target = static_cast<int>(g);
        ob.station = targets[g].station[k];
        ob.t = tr.usable_time(r);
        ob.o = tr.UsableRow(r);
        ob.o.station = ob.station;
        obs.push_back(ob);
        ++fit.rows[static_cast<std::size_t>(ob.station)];
      }
    }
  }
  if (obs.empty()) {
    throw DataError(stations.path, 0, 0,
                    "no time has two stations' lines of sight: the clock offsets cannot be estimated");
  }
  fit.observations = obs.size();
  std::vector<double> delta(S, 0.0);
  Built built;
  // Offsets as given: the path alone, the residuals the report compares with.
  fit.iterations += SolveReassigning(obs, splines, frames, delta, fit.reference, false, options, &built);
  fit.rms_arcsec_as_given = RmsArcsec(obs, splines, frames, delta);
  // Offsets free.
  fit.iterations += SolveReassigning(obs, splines, frames, delta, fit.reference, true, options, &built);
  fit.rms_arcsec_estimated = RmsArcsec(obs, splines, frames, delta);

  Covariance(built.problem.get(), splines, delta, obs, options, &fit);
  Warn(interval, options, &fit);
  return fit;
}

io::Json TimeOffsetFit::OffsetsJson() const {
  io::Json j = io::Json::object();
  for (std::size_t s = 0; s < names.size(); ++s) {
    io::Json e = {{"offset_s", offset_s[s]}, {"sigma_s", sigma_s[s]}, {"reference", s == reference},
                  {"start_s", start_s[s]}, {"rows", rows[s]}};
    if (s != reference) e["sigma_if_path_known_s"] = sigma_known_s[s];
    j[names[s]] = e;
  }
  return j;
}

io::Json TimeOffsetFit::FitJson() const {
  io::Json corr = io::Json::object();
  for (std::size_t a = 0; a < names.size(); ++a) {
    io::Json row = io::Json::object();
    for (std::size_t b = 0; b < names.size(); ++b) {
      row[names[b]] = correlation(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
    }
    corr[names[a]] = row;
  }
  return {{"reference", names[reference]},
          {"correlation", corr},
          {"rms_residual_arcsec", {{"offsets_as_given", rms_arcsec_as_given}, {"offsets_estimated", rms_arcsec_estimated}}},
          {"chi2_per_dof", chi2_per_dof},
          {"sigma_scale", sigma_scale},
          {"knot_interval_s", knot_interval_s},
          {"observations", observations},
          {"parameters", parameters},
          {"iterations", iterations},
          {"warnings", warnings}};
}

}  // namespace rk::intersect
