#include "registration/batch.h"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

#include "io/error.h"

namespace rk::registration {
namespace {

// Whitened difference of the two exact bias-corrected points of a pair; one 12-parameter block.
class PairResidual final : public ceres::SizedCostFunction<3, kBiasDim> {
 public:
  // W: the whitening of the pair's difference (3×3), or for a pair with a 2-D plot of its reduced difference
  // (d×d, radar_model.h ReducePair), whose residual is padded with 3 − d zeros.
  PairResidual(const PlotRecord& a, const PlotRecord& b, const MatX3& W, const MeasurementNoise& noise)
      : a_(a), b_(b), W_(W.rows() == 3 ? Mat3(W) : Mat3::Zero()), Wr_(W), noise_(noise) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Map<const BiasVector> x(parameters[0]);
    const RadarBias xa = x.head<kRadarBiasDim>(), xb = x.tail<kRadarBiasDim>();
    Eigen::Map<Vec3> r(residuals);
    if (!a_.meas.has_el || !b_.meas.has_el) {
      // The elevations are re-filled at x, so the residual is the reduced difference of the exact points; its
      // Jacobian is taken with U and the elevations held (their first-order effect is zero: Uᵀ ∂p/∂φ = 0).
      const auto [la, lb] = LinearizePair(a_.meas, a_.pose, xa, b_.meas, b_.pose, xb, noise_);
      const ReducedPair rp = ReducePair(la, lb, BiasVector(x));
      const int d = rp.dim;
      r.setZero();
      r.head(d) = Wr_ * rp.nu;
      if (jacobians != nullptr && jacobians[0] != nullptr) {
        Eigen::Map<Eigen::Matrix<double, 3, kBiasDim, Eigen::RowMajor>> J(jacobians[0]);
        J.setZero();
        J.topRows(d) = -Wr_ * rp.H;
      }
      return true;
    }
    if (jacobians == nullptr || jacobians[0] == nullptr) {
      r = W_ * (CorrectedEcefPoint(b_.meas, b_.pose, xb) - CorrectedEcefPoint(a_.meas, a_.pose, xa));
      return true;
    }
    const PlotLinearization la = LinearizePlot(a_.meas, a_.pose, xa, noise_);
    const PlotLinearization lb = LinearizePlot(b_.meas, b_.pose, xb, noise_);
    r = W_ * (lb.point_ecef - la.point_ecef);
    Eigen::Map<Eigen::Matrix<double, 3, kBiasDim, Eigen::RowMajor>> J(jacobians[0]);
    J.leftCols<kRadarBiasDim>() = -W_ * la.J;
    J.rightCols<kRadarBiasDim>() = W_ * lb.J;
    return true;
  }

 private:
  const PlotRecord& a_;
  const PlotRecord& b_;
  const Mat3 W_;
  const MatX3 Wr_;
  const MeasurementNoise noise_;
};

using PairList = std::vector<std::vector<std::pair<int, int>>>;

// d² of a pair for the estimate (x, P) (exact difference, linearised covariance), the whitening of its noise and
// its dimension: 3, or for a pair with a 2-D plot the reduced pair's (radar_model.h ReducePair).
double PairD2(const PlotRecord& a, const PlotRecord& b, const BiasVector& x, const BiasMatrix& P,
              const MeasurementNoise& noise, MatX3* W_out, int* dim = nullptr) {
  if (!a.meas.has_el || !b.meas.has_el) {
    const auto [la, lb] = LinearizePair(a.meas, a.pose, x.head<kRadarBiasDim>(), b.meas, b.pose,
                                        x.tail<kRadarBiasDim>(), noise);
    const ReducedPair rp = ReducePair(la, lb, x);
    if (dim) *dim = rp.dim;
    const MatX3 S = rp.H * P * rp.H.transpose() + rp.R;
    const Eigen::LLT<MatX3> llt(0.5 * (S + S.transpose()));
    if (llt.info() != Eigen::Success) return INFINITY;
    if (W_out) {
      const Eigen::LLT<MatX3> lr(rp.R);
      *W_out = lr.matrixL().solve(MatX3::Identity(rp.dim, rp.dim));
    }
    return llt.matrixL().solve(rp.nu).squaredNorm();
  }
  if (dim) *dim = 3;
  const PlotLinearization la = LinearizePlot(a.meas, a.pose, x.head<kRadarBiasDim>(), noise);
  const PlotLinearization lb = LinearizePlot(b.meas, b.pose, x.tail<kRadarBiasDim>(), noise);
  const PairMeasurement pm = MakePairMeasurement(la, lb);
  const Mat3 S = pm.H * P * pm.H.transpose() + pm.R;
  Eigen::LLT<Mat3> llt(0.5 * (S + S.transpose()));
  if (llt.info() != Eigen::Success) return INFINITY;
  if (W_out) {
    Eigen::LLT<Mat3> lr(pm.R);
    *W_out = Mat3(lr.matrixL().solve(Mat3::Identity()));
  }
  return llt.matrixL().solve(lb.point_ecef - la.point_ecef).squaredNorm();
}

PairList GateAssociation(const RegistrationInput& in, const BiasVector& x, const BiasMatrix& P,
                         const BatchOptions& opt) {
  PairList out(in.steps.size());
  struct Cand {
    double d2;
    int i, j;
  };
  std::vector<Cand> cands;
  std::vector<char> used_a, used_b;
  for (std::size_t k = 0; k < in.steps.size(); ++k) {
    const RegistrationStep& s = in.steps[k];
    if (!s.HasBothRadars()) continue;
    cands.clear();
    for (std::size_t i = 0; i < s.plots[0].size(); ++i) {
      for (std::size_t j = 0; j < s.plots[1].size(); ++j) {
        int dim = 3;
        const double d2 = PairD2(s.plots[0][i], s.plots[1][j], x, P, opt.initial.filter.noise, nullptr, &dim);
        if (d2 <= GateForDimension(opt.gate_d2, dim)) cands.push_back({d2, static_cast<int>(i), static_cast<int>(j)});
      }
    }
    std::sort(cands.begin(), cands.end(), [](const Cand& p, const Cand& q) { return p.d2 < q.d2; });
    used_a.assign(s.plots[0].size(), 0);
    used_b.assign(s.plots[1].size(), 0);
    for (const Cand& c : cands) {
      if (used_a[c.i] || used_b[c.j]) continue;
      used_a[c.i] = used_b[c.j] = 1;
      out[k].emplace_back(c.i, c.j);
    }
    std::sort(out[k].begin(), out[k].end());
  }
  return out;
}

PairList TrackAssociation(const RegistrationInput& in) {
  PairList out(in.steps.size());
  for (std::size_t k = 0; k < in.steps.size(); ++k) {
    const RegistrationStep& s = in.steps[k];
    for (std::size_t i = 0; i < s.plots[0].size(); ++i) {
      if (s.plots[0][i].track < 0) continue;
      for (std::size_t j = 0; j < s.plots[1].size(); ++j) {
        if (s.plots[1][j].track == s.plots[0][i].track) out[k].emplace_back(static_cast<int>(i), static_cast<int>(j));
      }
    }
  }
  return out;
}

std::int64_t CountPairs(const PairList& p) {
  std::int64_t n = 0;
  for (const auto& s : p) n += static_cast<std::int64_t>(s.size());
  return n;
}

std::int64_t Changes(const PairList& a, const PairList& b) {
  std::int64_t n = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    std::vector<std::pair<int, int>> diff;
    std::set_symmetric_difference(a[k].begin(), a[k].end(), b[k].begin(), b[k].end(), std::back_inserter(diff));
    n += static_cast<std::int64_t>(diff.size());
  }
  return n;
}

struct SolveOutcome {
  BiasVector x;
  BiasMatrix P;
  bool covariance_ok = false;
  ceres::Solver::Summary summary;
};

SolveOutcome Solve(const RegistrationInput& in, const PairList& pairs, const BiasVector& x0, const BatchOptions& opt) {
  SolveOutcome out;
  out.x = x0;
  // The loss outlives the problem that uses it (declared first, destroyed last).
  std::unique_ptr<ceres::LossFunction> loss;
  if (opt.loss == RobustLoss::kHuber) loss = std::make_unique<ceres::HuberLoss>(opt.loss_scale);
  if (opt.loss == RobustLoss::kCauchy) loss = std::make_unique<ceres::CauchyLoss>(opt.loss_scale);
  ceres::Problem::Options popt;
  popt.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(popt);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    for (const auto& [i, j] : pairs[k]) {
      const PlotRecord& a = in.steps[k].plots[0][i];
      const PlotRecord& b = in.steps[k].plots[1][j];
      MatX3 W;
      PairD2(a, b, x0, BiasMatrix::Zero(), opt.initial.filter.noise, &W);  // whitening at the start point
      problem.AddResidualBlock(new PairResidual(a, b, W, opt.initial.filter.noise), loss.get(), out.x.data());
    }
  }
  // A 2-D radar's el bias does not enter any residual (docs/rk-register.md "2-D radars"): held at its start value,
  // so that the covariance of the others exists.
  std::vector<int> constant;
  for (int r = 0; r < 2; ++r) {
    if (in.two_d[r]) constant.push_back(r * kRadarBiasDim + kBiasEl);
  }
  if (!constant.empty() && problem.NumResidualBlocks() > 0) {
    problem.SetManifold(out.x.data(), new ceres::SubsetManifold(kBiasDim, constant));
  }
  ceres::Solver::Options sopt;
  sopt.linear_solver_type = ceres::DENSE_QR;
  sopt.max_num_iterations = opt.max_iterations;
  sopt.num_threads = 1;
  sopt.function_tolerance = 1e-12;
  sopt.gradient_tolerance = 1e-14;
  sopt.parameter_tolerance = 1e-12;
  ceres::Solve(sopt, &problem, &out.summary);
  if (!out.summary.IsSolutionUsable()) {
    throw ProcessingError("batch solve failed: " + out.summary.message);
  }
  ceres::Covariance::Options copt;
  copt.algorithm_type = ceres::DENSE_SVD;
  copt.num_threads = 1;
  ceres::Covariance cov(copt);
  std::vector<std::pair<const double*, const double*>> blocks{{out.x.data(), out.x.data()}};
  out.P.setZero();
  if (cov.Compute(blocks, &problem)) {
    Eigen::Matrix<double, kBiasDim, kBiasDim, Eigen::RowMajor> C;
    out.covariance_ok = cov.GetCovarianceBlock(out.x.data(), out.x.data(), C.data());
    out.P = C;
  }
  return out;
}

}  // namespace

std::string BatchAssociationName(BatchAssociation a) {
  switch (a) {
    case BatchAssociation::kGate:
      return "gate";
    case BatchAssociation::kBernoulli:
      return "bernoulli";
    case BatchAssociation::kTrack:
      return "track";
  }
  return "gate";
}

std::string RobustLossName(RobustLoss loss) {
  return loss == RobustLoss::kHuber ? "huber" : loss == RobustLoss::kCauchy ? "cauchy" : "none";
}

const io::OptionTable<BatchOptions>& BatchOptions::Table() {
  using O = BatchOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Choice("--associate", &O::association,
                  {BatchAssociation::kGate, BatchAssociation::kBernoulli, BatchAssociation::kTrack},
                  BatchAssociationName, "gate, bernoulli or track")
          .Choice("--loss", &O::loss, {RobustLoss::kHuber, RobustLoss::kCauchy, RobustLoss::kNone}, RobustLossName,
                  "Robust loss: huber, cauchy or none")
          .Real("--loss-scale", &O::loss_scale, "", io::Bounds::Positive().Finite(),
                "Whitened residual norm beyond which the loss is no longer quadratic")
          .Real("--gate", &O::gate_d2, "", io::Bounds::Positive().Finite(),
                "Association gate on the pair's Mahalanobis distance squared")
          .Integer("--rounds", &O::max_rounds, "", io::Bounds::Closed(1, 50), "Association rounds at most (gate)")
          .Integer("--iterations", &O::max_iterations, "", io::Bounds::Closed(1, 1000),
                   "Ceres iterations per solve at most");
  return table;
}

bool BatchOptions::Check(std::string* why) const {
  return initial.Check(why) && Table().Check(*this, why);
}

io::Json BatchOptions::ToJson() const {
  io::Json j = Table().ToJson(*this);
  j["initial_bernoulli"] = initial.ToJson();
  return j;
}

io::Json BatchStats::ToJson() const {
  io::Json j;
  j["rounds"] = rounds;
  j["pairs"] = pairs;
  j["steps_with_pairs"] = steps_with_pairs;
  j["association_changes_last_round"] = association_changes;
  j["downweighted_pairs"] = downweighted;
  j["pairs_outside_gate"] = outside_gate;
  j["variance_factor"] = variance_factor;
  j["covariance_ok"] = covariance_ok;
  j["termination"] = termination;
  j["iterations"] = iterations;
  j["initial_cost"] = initial_cost;
  j["final_cost"] = final_cost;
  return j;
}

BatchResult RunBatch(const RegistrationInput& in, const BatchOptions& opt,
                     const std::function<void(std::int64_t)>& pass_progress,
                     const std::function<void(std::int64_t)>& solve_progress) {
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  if (opt.association == BatchAssociation::kTrack && !in.has_track_id) {
    throw DataError(in.plots_source, 1, 0, "missing column 'track_id': --associate track needs the known association");
  }
  BatchResult out;
  out.initial = RunBernoulli(in, opt.initial, pass_progress);
  BiasVector x = out.initial.result.x;
  BiasMatrix P = out.initial.result.P;
  PairList pairs;
  if (opt.association == BatchAssociation::kBernoulli) pairs = out.initial.selected;
  if (opt.association == BatchAssociation::kTrack) pairs = TrackAssociation(in);
  const int rounds = opt.association == BatchAssociation::kGate ? opt.max_rounds : 1;
  SolveOutcome sol;
  for (int round = 0; round < rounds; ++round) {
    if (opt.association == BatchAssociation::kGate) {
      PairList next = GateAssociation(in, x, P, opt);
      out.stats.association_changes = round == 0 ? CountPairs(next) : Changes(pairs, next);
      if (round > 0 && out.stats.association_changes == 0) break;
      pairs = std::move(next);
    }
    if (CountPairs(pairs) == 0) throw ProcessingError("batch: no pair of plots could be associated");
    sol = Solve(in, pairs, x, opt);
    ++out.stats.rounds;
    out.stats.iterations += static_cast<int>(sol.summary.iterations.size());
    x = sol.x;
    if (sol.covariance_ok) P = sol.P;
    if (solve_progress) solve_progress(out.stats.rounds);
  }
  out.pairs = pairs;
  out.stats.pairs = CountPairs(pairs);
  out.stats.covariance_ok = sol.covariance_ok;
  out.stats.termination = ceres::TerminationTypeToString(sol.summary.termination_type);
  out.stats.initial_cost = sol.summary.initial_cost;
  out.stats.final_cost = sol.summary.final_cost;

  // Residual statistics at the solution.
  double chi2 = 0;
  std::int64_t residual_dims = 0;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (!pairs[k].empty()) ++out.stats.steps_with_pairs;
    for (const auto& [i, j] : pairs[k]) {
      int dim = 3;
      const double e2 = PairD2(in.steps[k].plots[0][i], in.steps[k].plots[1][j], x, BiasMatrix::Zero(),
                               opt.initial.filter.noise, nullptr, &dim);
      chi2 += e2;
      residual_dims += dim;
      if (e2 > opt.loss_scale * opt.loss_scale) ++out.stats.downweighted;
      if (e2 > GateForDimension(opt.gate_d2, dim)) ++out.stats.outside_gate;
    }
  }
  const int free_biases = kBiasDim - (in.two_d[0] ? 1 : 0) - (in.two_d[1] ? 1 : 0);
  const double dof = static_cast<double>(residual_dims) - free_biases;
  out.stats.variance_factor = dof > 0 ? chi2 / dof : 0.0;

  RegistrationResult& r = out.result;
  r.method = "batch";
  r.x = x;
  r.P = sol.covariance_ok ? sol.P : BiasMatrix::Constant(NAN);
  const BiasVector sigma = sol.covariance_ok ? BiasVector(sol.P.diagonal().cwiseMax(0.0).cwiseSqrt())
                                             : BiasVector::Constant(NAN);
  for (std::size_t k = 0; k < in.steps.size(); ++k) {
    StepEstimate e;
    e.t_s = in.steps[k].t_s;
    e.x = x;
    e.sigma = sigma;
    e.pairs_used = static_cast<int>(pairs[k].size());
    e.status = pairs[k].empty() ? RowStatus::kPredicted : RowStatus::kOk;
    r.steps.push_back(e);
  }
  r.unobservable = UnobservableBiases(in, r.P, opt.initial.filter.initial_sigma);
  r.stats = out.stats.ToJson();
  r.stats["options"] = opt.ToJson();
  r.stats["initial_bernoulli"] = out.initial.result.stats;
  r.stats["initial_bernoulli"].erase("options");
  r.stats["ceres_report"] = sol.summary.BriefReport();
  return out;
}

}  // namespace rk::registration
