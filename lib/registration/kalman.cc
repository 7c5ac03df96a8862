#include "registration/kalman.h"

#include "io/error.h"

namespace rk::registration {
namespace {
constexpr double kChi2Dof3P999 = 16.27;  // chi-square 3 dof, 0.999 quantile
}

bool KfOptions::Check(std::string* why) const {
  if (!filter.Check(why)) return false;
  if (track.empty()) {
    if (why) *why = "track must be 'all' or a track_id";
    return false;
  }
  return true;
}

io::Json KfOptions::ToJson() const {
  io::Json j = filter.ToJson();
  j["track"] = track;
  return j;
}

KfResult RunKalman(const RegistrationInput& in, const KfOptions& opt, const std::function<void(std::int64_t)>& progress) {
  std::string why;
  if (!opt.Check(&why)) throw UsageError(why);
  if (!in.has_track_id) {
    throw DataError(in.plots_source, 1, 0, "missing column 'track_id': rk-register kf needs the known association");
  }
  int only = -1;
  if (opt.track != "all") {
    for (std::size_t i = 0; i < in.track_ids.size(); ++i) {
      if (in.track_ids[i] == opt.track) only = static_cast<int>(i);
    }
    if (only < 0) throw UsageError("--track " + opt.track + ": no plot has this track_id");
  }
  KfResult out;
  out.result.method = "kf";
  out.used.resize(in.steps.size());
  BiasVector m = BiasVector::Zero();
  BiasMatrix P = InitialCovariance(opt.filter);
  const BiasMatrix Q = ProcessCovariance(opt.filter);
  double nis_sum = 0;
  std::int64_t dof_sum = 0;
  for (std::size_t k = 0; k < in.steps.size(); ++k) {
    const RegistrationStep& step = in.steps[k];
    ++out.counters.steps;
    P += Q;
    const BiasVector lin_at = opt.filter.linearization == Linearization::kEstimate ? m : BiasVector::Zero();
    auto& used = out.used[k];
    for (std::size_t i = 0; i < step.plots[0].size(); ++i) {
      const PlotRecord& a = step.plots[0][i];
      if (a.track < 0 || (only >= 0 && a.track != only)) continue;
      for (std::size_t j = 0; j < step.plots[1].size(); ++j) {
        const PlotRecord& b = step.plots[1][j];
        if (b.track != a.track) continue;
        const auto [la, lb] = LinearizePair(a.meas, a.pose, lin_at.head<kRadarBiasDim>(), b.meas, b.pose,
                                            lin_at.tail<kRadarBiasDim>(), opt.filter.noise);
        double d2 = 0;
        int dim = 3;
        if (UpdateWithPair(la, lb, &m, &P, &out.counters, &d2, nullptr, &dim)) {
          used.emplace_back(static_cast<int>(i), static_cast<int>(j));
          nis_sum += d2;
          dof_sum += dim;
          if (d2 > GateForDimension(kChi2Dof3P999, dim)) ++out.large_innovations;
        }
      }
    }
    StepEstimate est;
    est.t_s = step.t_s;
    est.x = m;
    est.sigma = P.diagonal().cwiseMax(0.0).cwiseSqrt();
    est.pairs_used = static_cast<int>(used.size());
    est.status = used.empty() ? RowStatus::kPredicted : RowStatus::kOk;
    if (used.empty()) {
      ++out.counters.steps_predicted;
    } else {
      ++out.counters.steps_updated;
    }
    out.result.steps.push_back(est);
    if (progress) progress(static_cast<std::int64_t>(k) + 1);
  }
  out.result.x = m;
  out.result.P = P;
  out.mean_nis = out.counters.updates > 0 ? nis_sum / static_cast<double>(out.counters.updates) : 0.0;
  out.mean_dof = out.counters.updates > 0 ? static_cast<double>(dof_sum) / static_cast<double>(out.counters.updates) : 0.0;
  out.result.unobservable = UnobservableBiases(in, P, opt.filter.initial_sigma);
  out.result.stats = out.counters.ToJson();
  out.result.stats["large_innovations"] = out.large_innovations;
  out.result.stats["mean_nis"] = out.mean_nis;
  if (out.mean_dof < 3.0) out.result.stats["mean_nis_dof"] = out.mean_dof;  // pairs with 2-D plots only
  out.result.stats["options"] = opt.ToJson();
  return out;
}

}  // namespace rk::registration
