#include "registration/bernoulli.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "io/error.h"

namespace rk::registration {
namespace {

// Floor of each extent of the differences' bounding box (m) when κ is estimated: keeps the
// volume finite when all plots of a radar coincide.
constexpr double kMinBoxExtentM = 1.0;
// ln κ when no false difference is expected (one plot per radar): effectively −∞, kept finite
// so that sums of scores stay ordinary numbers.
constexpr double kLogKappaNoClutter = -690.0;

struct Path {
  BiasVector m;
  BiasMatrix P;
  double score = 0.0;  // Σ member scores (lower = more likely)
  int n = 0;
  std::array<int, kMaxSubsetLength> ia{}, ib{};
  bool stopped = false;

  bool UsesA(int i) const {
    for (int k = 0; k < n; ++k)
      if (ia[k] == i) return true;
    return false;
  }
  bool UsesB(int j) const {
    for (int k = 0; k < n; ++k)
      if (ib[k] == j) return true;
    return false;
  }
  bool UsesPair(int i, int j) const {
    for (int k = 0; k < n; ++k)
      if (ia[k] == i && ib[k] == j) return true;
    return false;
  }
  // Same member set as `o` plus (i, j) (j < 0: o itself)?
  bool SameSetAs(const Path& o, int i, int j) const {
    const int on = o.n + (j >= 0 ? 1 : 0);
    if (on != n) return false;
    for (int k = 0; k < n; ++k) {
      const bool in_o = o.UsesPair(ia[k], ib[k]) || (ia[k] == i && ib[k] == j);
      if (!in_o) return false;
    }
    return true;
  }
};

struct Component {
  double log_w = 0.0;
  BiasVector m = BiasVector::Zero();
  BiasMatrix P = BiasMatrix::Identity();
  std::vector<std::pair<int, int>> members;
};

struct Candidate {
  int path = 0;
  int i = -1, j = -1;  // j < 0: the path stops here
  double score = 0.0;  // total score of the resulting subset
};

struct PlotTerms {
  Vec3 g;   // linearised corrected point at the path's mean
  Mat3 S;   // J P_rr Jᵀ + noise (r = own radar block)
  Mat36 W;  // radar a only: J P_ab
};

double LogSumExp(const std::vector<Component>& c) {
  double mx = -std::numeric_limits<double>::infinity();
  for (const Component& x : c) mx = std::max(mx, x.log_w);
  double s = 0;
  for (const Component& x : c) s += std::exp(x.log_w - mx);
  return mx + std::log(s);
}

class BernoulliFilter {
 public:
  BernoulliFilter(const RegistrationInput& in, const BernoulliOptions& opt)
      : in_(in), opt_(opt), Q_(ProcessCovariance(opt.filter)) {
    Component c;
    c.P = InitialCovariance(opt.filter);
    comps_.push_back(c);
  }

  BernoulliResult Run(const std::function<void(std::int64_t)>& progress) {
    BernoulliResult out;
    out.result.method = "bernoulli";
    out.result.steps.reserve(in_.steps.size());
    out.selected.resize(in_.steps.size());
    double comp_sum = 0;
    for (std::size_t k = 0; k < in_.steps.size(); ++k) {
      const RegistrationStep& step = in_.steps[k];
      ++stats_.counters.steps;
      for (Component& c : comps_) c.P += Q_;
      StepEstimate est;
      est.t_s = step.t_s;
      std::vector<std::pair<int, int>> selected;
      if (step.HasBothRadars()) Update(step, &selected);
      const Component& best = comps_.front();  // sorted heaviest first
      est.x = best.m;
      est.sigma = best.P.diagonal().cwiseMax(0.0).cwiseSqrt();
      est.components = static_cast<int>(comps_.size());
      est.pairs_used = static_cast<int>(selected.size());
      est.status = selected.empty() ? RowStatus::kPredicted : RowStatus::kOk;
      if (selected.empty()) {
        ++stats_.counters.steps_predicted;
      } else {
        ++stats_.counters.steps_updated;
        stats_.reported_members += static_cast<std::int64_t>(selected.size());
        if (static_cast<int>(selected.size()) < opt_.subset_length) ++stats_.short_subsets;
      }
      stats_.max_components = std::max<std::int64_t>(stats_.max_components, est.components);
      comp_sum += est.components;
      out.selected[k] = std::move(selected);
      out.result.steps.push_back(est);
      if (progress) progress(static_cast<std::int64_t>(k) + 1);
    }
    stats_.mean_components = in_.steps.empty() ? 0.0 : comp_sum / static_cast<double>(in_.steps.size());
    out.result.x = comps_.front().m;
    out.result.P = comps_.front().P;
    out.result.unobservable = UnobservableBiases(in_, out.result.P, opt_.filter.initial_sigma);
    out.stats = stats_;
    out.result.stats = stats_.ToJson();
    out.result.stats["options"] = opt_.ToJson();
    return out;
  }

 private:
  void Linearize(const RegistrationStep& step, const BiasVector& at) {
    for (int r = 0; r < 2; ++r) {
      auto& lin = r == 0 ? lin_a_ : lin_b_;
      lin.resize(step.plots[r].size());
      const RadarBias b0 = r == 0 ? RadarBias(at.head<kRadarBiasDim>()) : RadarBias(at.tail<kRadarBiasDim>());
      for (std::size_t i = 0; i < lin.size(); ++i) {
        const PlotRecord& p = step.plots[r][i];
        lin[i] = LinearizePlot(p.meas, p.pose, b0, opt_.filter.noise);
      }
    }
    // Pairs with a 2-D plot: both plots linearised with the pair's elevations (radar_model.h FillMissingElevations).
    const std::size_t na = step.plots[0].size(), nb = step.plots[1].size();
    pair_lin_.resize(na * nb);
    if (!step_has_2d_) return;
    for (std::size_t i = 0; i < na; ++i) {
      for (std::size_t j = 0; j < nb; ++j) {
        const PlotRecord& a = step.plots[0][i];
        const PlotRecord& b = step.plots[1][j];
        if (a.meas.has_el && b.meas.has_el) continue;
        pair_lin_[i * nb + j] = LinearizePair(a.meas, a.pose, at.head<kRadarBiasDim>(), b.meas, b.pose,
                                              at.tail<kRadarBiasDim>(), opt_.filter.noise);
      }
    }
  }

  bool IsReduced(int i, int j) const { return !lin_a_[i].has_el || !lin_b_[j].has_el; }
  const PlotLinearization& LinA(int i, int j) const {
    return IsReduced(i, j) ? pair_lin_[i * lin_b_.size() + j].first : lin_a_[i];
  }
  const PlotLinearization& LinB(int i, int j) const {
    return IsReduced(i, j) ? pair_lin_[i * lin_b_.size() + j].second : lin_b_[j];
  }

  // ln κ_d of this step for a pair of dimension d (clutter density of the differences, per m^d). κ_3 is the
  // density of the 3-D differences; a reduced pair's differences are their projections on a d-dimensional
  // subspace, whose density is n_false / V^(d/3) for n_false differences spread over a volume V = n_false / κ_3:
  // ln κ_d = (1 − d/3) ln n_false + (d/3) ln κ_3.
  double LogKappa(const RegistrationStep& step, int dim) const {
    const double na = static_cast<double>(step.plots[0].size()), nb = static_cast<double>(step.plots[1].size());
    const double n_false = na * nb - std::min(na, nb);
    if (dim == 3) {
      if (opt_.clutter_density > 0) return std::log(opt_.clutter_density);
      return n_false <= 0 ? kLogKappaNoClutter : LogKappa3(step, n_false);
    }
    const double f = dim / 3.0;
    if (opt_.clutter_density > 0) return (1.0 - f) * std::log(std::max(n_false, 1.0)) + f * std::log(opt_.clutter_density);
    if (n_false <= 0) return kLogKappaNoClutter;
    return (1.0 - f) * std::log(n_false) + f * LogKappa3(step, n_false);
  }

  double LogKappa3(const RegistrationStep& step, double n_false) const {
    double volume = 1.0;
    std::array<Vec3, 2> lo, hi;
    for (int r = 0; r < 2; ++r) {
      lo[r] = Vec3::Constant(std::numeric_limits<double>::infinity());
      hi[r] = -lo[r];
      for (const PlotRecord& p : step.plots[r]) {
        const Vec3 x = CorrectedEcefPoint(p.meas, p.pose, RadarBias::Zero());
        lo[r] = lo[r].cwiseMin(x);
        hi[r] = hi[r].cwiseMax(x);
      }
    }
    for (int d = 0; d < 3; ++d) {
      volume *= std::max(kMinBoxExtentM, (hi[0][d] - lo[0][d]) + (hi[1][d] - lo[1][d]));
    }
    return std::log(n_false / volume);
  }

  void ComputeTerms(const Path& p) {
    const Eigen::Matrix<double, 6, 6> Paa = p.P.topLeftCorner<6, 6>(), Pab = p.P.topRightCorner<6, 6>(),
                                      Pbb = p.P.bottomRightCorner<6, 6>();
    const RadarBias ma = p.m.head<kRadarBiasDim>(), mb = p.m.tail<kRadarBiasDim>();
    terms_a_.resize(lin_a_.size());
    terms_b_.resize(lin_b_.size());
    for (std::size_t i = 0; i < lin_a_.size(); ++i) {
      const Mat36& J = lin_a_[i].J;
      terms_a_[i].g = lin_a_[i].PointAt(ma);
      terms_a_[i].S = J * Paa * J.transpose() + lin_a_[i].noise_cov;
      terms_a_[i].W = J * Pab;
    }
    for (std::size_t j = 0; j < lin_b_.size(); ++j) {
      const Mat36& J = lin_b_[j].J;
      terms_b_[j].g = lin_b_[j].PointAt(mb);
      terms_b_[j].S = J * Pbb * J.transpose() + lin_b_[j].noise_cov;
    }
  }

  // Scores every admissible extension of paths_[p] and appends the gated ones to cands_.
  void ScorePath(int p, double member_offset) {
    const Path& path = paths_[p];
    ComputeTerms(path);
    const int na = static_cast<int>(lin_a_.size()), nb = static_cast<int>(lin_b_.size());
    for (int i = 0; i < na; ++i) {
      if (opt_.exclusive_plots() && path.UsesA(i)) continue;
      const PlotTerms& ta = terms_a_[i];
      for (int j = 0; j < nb; ++j) {
        if (opt_.exclusive_plots() ? path.UsesB(j) : path.UsesPair(i, j)) continue;
        if (IsReduced(i, j)) {
          ScoreReducedPair(p, i, j);
          continue;
        }
        const PlotTerms& tb = terms_b_[j];
        ++stats_.counters.pairs_evaluated;
        const Mat3 X = ta.W * lin_b_[j].J.transpose();
        Mat3 S = ta.S + tb.S - X - X.transpose();
        const Vec3 nu = tb.g - ta.g;
        Eigen::LLT<Mat3> llt(S);
        if (llt.info() != Eigen::Success) {
          ++stats_.counters.innovation_not_pd;
          continue;
        }
        const Vec3 w = llt.matrixL().solve(nu);
        const double d2 = w.squaredNorm();
        if (d2 > opt_.gate_d2) continue;
        ++stats_.gated_pairs;
        const Mat3& L = llt.matrixLLT();
        const double cost = 0.5 * d2 + 1.5 * kLog2Pi + std::log(L(0, 0) * L(1, 1) * L(2, 2));  // −ln q
        const double score = cost + member_offset;
        if (allow_stop_ && score >= 0) continue;  // worse than "false difference + missed target"
        cands_.push_back({p, i, j, path.score + score});
      }
    }
  }

  // ScorePath for a pair with a 2-D plot: the reduced pair (dimension d < 3), its own gate and clutter density.
  void ScoreReducedPair(int p, int i, int j) {
    const Path& path = paths_[p];
    ++stats_.counters.pairs_evaluated;
    const ReducedPair rp = ReducePair(LinA(i, j), LinB(i, j), path.m);
    const MatX3 S = rp.H * path.P * rp.H.transpose() + rp.R;
    const Eigen::LLT<MatX3> llt(0.5 * (S + S.transpose()));
    if (llt.info() != Eigen::Success) {
      ++stats_.counters.innovation_not_pd;
      return;
    }
    const double d2 = llt.matrixL().solve(rp.nu).squaredNorm();
    if (d2 > gate_[rp.dim]) return;
    ++stats_.gated_pairs;
    const MatX3 L = llt.matrixL();
    const double cost = 0.5 * d2 + 0.5 * rp.dim * kLog2Pi + L.diagonal().array().log().sum();  // −ln q
    const double score = cost + member_offset_[rp.dim];
    if (allow_stop_ && score >= 0) return;
    cands_.push_back({p, i, j, path.score + score});
  }

  void Update(const RegistrationStep& step, std::vector<std::pair<int, int>>* selected) {
    step_has_2d_ = false;
    for (int r = 0; r < 2; ++r) {
      for (const PlotRecord& p : step.plots[r]) step_has_2d_ = step_has_2d_ || !p.meas.has_el;
    }
    const double log_kappa = LogKappa(step, 3);
    const double pd = opt_.detection_probability;
    allow_stop_ = pd < 1.0;
    // Member score = −ln q + ln κ − ln(p_D / (1 − p_D)).
    const double member_offset = log_kappa - (allow_stop_ ? std::log(pd / (1.0 - pd)) : 0.0);
    if (step_has_2d_) {
      for (int d = 1; d <= 2; ++d) {
        member_offset_[d] = LogKappa(step, d) - (allow_stop_ ? std::log(pd / (1.0 - pd)) : 0.0);
        gate_[d] = GateForDimension(opt_.gate_d2, d);
      }
    }
    stats_.differences += static_cast<std::int64_t>(step.plots[0].size() * step.plots[1].size());
    if (opt_.filter.linearization == Linearization::kMeasured) Linearize(step, BiasVector::Zero());

    children_.clear();
    for (const Component& comp : comps_) {
      if (opt_.filter.linearization == Linearization::kEstimate) Linearize(step, comp.m);
      paths_.clear();
      Path root;
      root.m = comp.m;
      root.P = comp.P;
      paths_.push_back(root);
      for (int level = 0; level < opt_.subset_length; ++level) {
        cands_.clear();
        bool any_open = false;
        for (int p = 0; p < static_cast<int>(paths_.size()); ++p) {
          if (allow_stop_ || paths_[p].stopped) cands_.push_back({p, -1, -1, paths_[p].score});
          if (paths_[p].stopped) continue;
          any_open = true;
          const std::size_t before = cands_.size();
          ScorePath(p, member_offset);
          if (!allow_stop_ && cands_.size() == before) {
            cands_.push_back({p, -1, -1, paths_[p].score});  // p_D = 1 but nothing gated: forced stop
          }
        }
        if (!any_open) break;
        std::sort(cands_.begin(), cands_.end(),
                  [](const Candidate& x, const Candidate& y) { return x.score < y.score; });
        next_.clear();
        for (const Candidate& c : cands_) {
          const Path& parent = paths_[c.path];
          bool dup = false;
          for (const Path& q : next_) {
            if (q.SameSetAs(parent, c.i, c.j)) {
              dup = true;
              break;
            }
          }
          if (dup) continue;
          Path child = parent;
          if (c.j < 0) {
            child.stopped = true;
          } else {
            if (!UpdateWithPair(LinA(c.i, c.j), LinB(c.i, c.j), &child.m, &child.P, &stats_.counters)) continue;
            child.ia[child.n] = c.i;
            child.ib[child.n] = c.j;
            ++child.n;
            child.score = c.score;
          }
          next_.push_back(child);
          if (static_cast<int>(next_.size()) == opt_.subsets) break;
        }
        paths_.swap(next_);
      }
      for (const Path& p : paths_) {
        Component c;
        c.log_w = comp.log_w - p.score;
        c.m = p.m;
        c.P = p.P;
        for (int k = 0; k < p.n; ++k) c.members.emplace_back(p.ia[k], p.ib[k]);
        children_.push_back(std::move(c));
      }
    }
    PruneAndMerge();
    *selected = comps_.front().members;
  }

  // Normalise (eq. 42), prune, merge, cap; leaves comps_ sorted heaviest first.
  void PruneAndMerge() {
    std::sort(children_.begin(), children_.end(),
              [](const Component& a, const Component& b) { return a.log_w > b.log_w; });
    const double lse = LogSumExp(children_);
    for (Component& c : children_) c.log_w -= lse;
    const double log_prune = opt_.prune_weight > 0 ? std::log(opt_.prune_weight) : -1e300;
    std::size_t keep = 1;
    while (keep < children_.size() && children_[keep].log_w >= log_prune) ++keep;
    children_.resize(keep);

    comps_.clear();
    std::vector<bool> used(children_.size(), false);
    for (std::size_t j = 0; j < children_.size(); ++j) {
      if (used[j]) continue;
      const Component& head = children_[j];
      used[j] = true;
      group_.assign(1, j);
      if (opt_.merge_d2 > 0) {
        for (std::size_t i = j + 1; i < children_.size(); ++i) {
          if (used[i]) continue;
          Eigen::LLT<BiasMatrix> llt(children_[i].P);
          if (llt.info() != Eigen::Success) continue;
          const BiasVector d = children_[i].m - head.m;
          const double d2 = llt.matrixL().solve(d).squaredNorm();
          if (d2 <= opt_.merge_d2) {
            used[i] = true;
            group_.push_back(i);
          }
        }
      }
      Component merged;
      merged.members = head.members;
      if (group_.size() == 1) {
        merged.log_w = head.log_w;
        merged.m = head.m;
        merged.P = head.P;
      } else {
        double wsum = 0;
        BiasVector m = BiasVector::Zero();
        for (std::size_t g : group_) {
          const double w = std::exp(children_[g].log_w - head.log_w);
          wsum += w;
          m += w * children_[g].m;
        }
        m /= wsum;
        BiasMatrix P = BiasMatrix::Zero();
        for (std::size_t g : group_) {
          const double w = std::exp(children_[g].log_w - head.log_w);
          const BiasVector d = children_[g].m - m;
          P += w * (children_[g].P + d * d.transpose());
        }
        P /= wsum;
        if (SymmetrizeAndRepair(&P)) ++stats_.counters.covariance_repairs;
        merged.log_w = head.log_w + std::log(wsum);
        merged.m = m;
        merged.P = P;
      }
      comps_.push_back(std::move(merged));
    }
    std::sort(comps_.begin(), comps_.end(), [](const Component& a, const Component& b) { return a.log_w > b.log_w; });
    if (static_cast<int>(comps_.size()) > opt_.max_components) comps_.resize(opt_.max_components);
    const double lse2 = LogSumExp(comps_);
    for (Component& c : comps_) c.log_w -= lse2;
  }

  const RegistrationInput& in_;
  const BernoulliOptions& opt_;
  const BiasMatrix Q_;
  BernoulliStats stats_;
  bool allow_stop_ = true;
  std::vector<Component> comps_, children_;
  std::vector<PlotLinearization> lin_a_, lin_b_;
  // Pairs with a 2-D plot (step_has_2d_): the pair's two linearisations, index i·n_b + j.
  std::vector<std::pair<PlotLinearization, PlotLinearization>> pair_lin_;
  bool step_has_2d_ = false;
  std::array<double, 3> member_offset_{}, gate_{};  // reduced pairs, by dimension d = 1, 2
  std::vector<PlotTerms> terms_a_, terms_b_;
  std::vector<Path> paths_, next_;
  std::vector<Candidate> cands_;
  std::vector<std::size_t> group_;
};

}  // namespace

namespace {

// The Bernoulli options in --help order; `standalone` adds those rk-register batch's pass does not take.
io::OptionTable<BernoulliOptions> MakeBernoulliTable(bool standalone) {
  using O = BernoulliOptions;
  io::OptionTable<O> t;
  t.Integer("--subsets", &O::subsets, "", io::Bounds::Closed(1, 64),
            "Greedy partition: number of subsets K kept per component")
      .Alias("-K")
      .Integer("--subset-length", &O::subset_length, "", io::Bounds::Closed(1, kMaxSubsetLength),
               "Greedy partition: subset length L (pairs per component and step); 1 = no partition")
      .Alias("-L");
  if (standalone) {
    t.Real("--gate", &O::gate_d2, "", io::Bounds::Positive().Finite(),
           "Gate on the pair's Mahalanobis distance squared (3 dof)");
  }
  t.Real("--pd", &O::detection_probability, "", io::Bounds::LeftOpen(0.0, 1.0),
         "Detection probability p_D in (0, 1]; 1 = the paper's no-missed-detection subsets")
      .Real("--clutter-density", &O::clutter_density, "per m^3", io::Bounds::AtLeast(0.0).Finite(),
            "Density of false differences (per m^3); 0 = estimated per step")
      .Real("--prune", &O::prune_weight, "", io::Bounds::RightOpen(0.0, 1.0),
            "Prune components lighter than this weight")
      .Real("--merge", &O::merge_d2, "", io::Bounds::AtLeast(0.0).Finite(),
            "Merge components within this Mahalanobis distance squared")
      .Integer("--max-components", &O::max_components, "", io::Bounds::Closed(1, 256),
               "Keep at most this many Gaussian components");
  if (standalone) {
    t.Flag("--allow-plot-reuse", &O::allow_plot_reuse,
           "Let a subset use one plot in several pairs (the paper excludes only repeated pairs)");
  }
  return t;
}

}  // namespace

const io::OptionTable<BernoulliOptions>& BernoulliOptions::Table() {
  static const io::OptionTable<BernoulliOptions> table = MakeBernoulliTable(true);
  return table;
}

const io::OptionTable<BernoulliOptions>& BernoulliOptions::PassTable() {
  static const io::OptionTable<BernoulliOptions> table = MakeBernoulliTable(false);
  return table;
}

bool BernoulliOptions::Check(std::string* why) const {
  return filter.Check(why) && Table().Check(*this, why);
}

io::Json BernoulliOptions::ToJson() const {
  io::Json j = filter.ToJson();
  j.update(Table().ToJson(*this));
  return j;
}

io::Json BernoulliStats::ToJson() const {
  io::Json j = counters.ToJson();
  j["differences"] = differences;
  j["gated_pairs"] = gated_pairs;
  j["reported_members"] = reported_members;
  j["mean_subset_length"] =
      counters.steps_updated > 0 ? static_cast<double>(reported_members) / counters.steps_updated : 0.0;
  j["short_subsets"] = short_subsets;
  j["max_components"] = max_components;
  j["mean_components"] = mean_components;
  return j;
}

BernoulliResult RunBernoulli(const RegistrationInput& input, const BernoulliOptions& options,
                             const std::function<void(std::int64_t)>& progress) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  BernoulliFilter f(input, options);
  return f.Run(progress);
}

}  // namespace rk::registration
