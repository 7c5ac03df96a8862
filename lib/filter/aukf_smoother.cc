// The AUKF's Rauch–Tung–Striebel smoother (aukf_internal.h).
#include <algorithm>

#include "filter/aukf_internal.h"

namespace rk::filter::aukf_detail {

void RtsSmooth(const AukfOptions& options, const IntervalNoise& intervals, Model* model, AukfResult* res) {
  const int m = res->m;
  const int n = res->n;
  const std::size_t mu = static_cast<std::size_t>(m);
  const std::size_t J = res->t_s.size();
  const std::size_t packed = static_cast<std::size_t>(n * (n + 1) / 2);
  res->x_smooth.resize(n, static_cast<Eigen::Index>(J));
  res->sd_smooth.resize(n, static_cast<Eigen::Index>(J));
  StateVec xs = res->x_filter.col(static_cast<Eigen::Index>(J - 1));
  StateMat Ps;
  Unpack(res->cov_filter.data() + (J - 1) * packed, n, &Ps);
  res->x_smooth.col(static_cast<Eigen::Index>(J - 1)) = xs;
  res->sd_smooth.col(static_cast<Eigen::Index>(J - 1)) = Ps.diagonal().cwiseMax(0.0).cwiseSqrt();
  std::size_t smoother_repairs = 0;
  std::vector<std::size_t> q_offset;  // packed offset of each interval's adapted Q
  if (intervals.store_q) {
    std::size_t off = 0;
    for (char u : intervals.q_store_used) {
      q_offset.push_back(off);
      if (u) off += packed;
    }
  }
  StateMat Qr_k;
  for (std::size_t jj = J - 1; jj-- > 0;) {
    const StateVec xf = res->x_filter.col(static_cast<Eigen::Index>(jj));
    StateMat Pf;
    Unpack(res->cov_filter.data() + jj * packed, n, &Pf);
    const double s = res->t_s[jj + 1] - res->t_s[jj];
    const std::size_t interval = jj / 2;  // nodes 2i (sample i) and 2i+1 (mid) lie in interval i → i+1
    const StateMat* Qr = nullptr;
    if (intervals.store_q && intervals.q_store_used[interval]) {
      Unpack(intervals.q_store.data() + q_offset[interval], n, &Qr_k);
      Qr = &Qr_k;
    }
    if (intervals.store_model_q) {
      std::copy_n(intervals.model_q_store.begin() + static_cast<std::ptrdiff_t>(interval * mu), mu, model->q.begin());
    }
    StateVec xp;
    StateMat Pp;
    StateMat C;
    model->Predict(xf, &Pf, s, Qr, &xp, &Pp, &smoother_repairs, &C);
    Eigen::LLT<StateMat> llt(Pp);
    if (llt.info() != Eigen::Success) {
      ukf::RepairSpd(&Pp, model->scale, model->p_floor);
      ++smoother_repairs;
      llt.compute(Pp);
    }
    StateMat G = llt.solve(C.transpose()).transpose();
    // A column that starts at node jj + 1 was not predicted from node jj: nothing flows back to it.
    for (int c = 0; c < m; ++c) {
      const std::size_t f = res->first_row[static_cast<std::size_t>(c)];
      if (f > 0 && jj + 1 == 2 * f) G.middleRows(3 * c, 3).setZero();
    }
    StateVec diff = xs - xp;
    ukf::WrapAngles(model->angles, &diff);
    StateVec xs_new = xf + G * diff;
    ukf::WrapAngles(model->angles, &xs_new);
    StateMat Ps_new = Pf + G * (Ps - Pp) * G.transpose();
    ukf::Symmetrise(&Ps_new);
    xs = xs_new;
    Ps = Ps_new;
    res->x_smooth.col(static_cast<Eigen::Index>(jj)) = xs;
    res->sd_smooth.col(static_cast<Eigen::Index>(jj)) = Ps.diagonal().cwiseMax(0.0).cwiseSqrt();
  }
  res->p_repairs += smoother_repairs;
  if (!options.keep_covariance) {
    res->cov_filter.clear();
    res->cov_filter.shrink_to_fit();
  }
}

}  // namespace rk::filter::aukf_detail
