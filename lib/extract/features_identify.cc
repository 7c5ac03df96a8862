// Marker identification by affine-camera hypotheses; method in features_identify.h.
#include "extract/features_identify.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <tuple>

namespace rk::extract {
namespace {

struct Record {
  std::vector<int> det_of_model;
  int inliers = 0;
  double sse = 0.0;
  double rms = 0.0;
  double tol = 0.0;
  Eigen::Matrix<double, 2, 4> A = Eigen::Matrix<double, 2, 4>::Zero();
};

bool Better(const Record& a, const Record& b) {
  return a.inliers != b.inliers ? a.inliers > b.inliers : a.sse < b.sse;
}

// k model points (k = 3 planar, 4 otherwise) and the inverse of their columns (q, 1).
struct Basis {
  std::vector<int> idx;
  double measure = 0.0;
  Eigen::Matrix4d inv = Eigen::Matrix4d::Zero();  // k × k inverse of the columns (q, 1) (top-left)
};

// Every well-conditioned k-subset of the model points, largest volume (area) first.
std::vector<Basis> AllBases(const AffineCameraModel& affine, std::size_t n, int k) {
  const bool planar = affine.planar();
  std::vector<Basis> all;
  std::vector<int> sel(static_cast<std::size_t>(k));
  std::function<void(int, int)> rec = [&](int start, int depth) {
    if (depth == k) {
      Basis b;
      b.idx = sel;
      if (planar) {
        Eigen::Matrix3d B;
        for (int c = 0; c < 3; ++c) {
          const Eigen::Vector3d& q = affine.q(static_cast<std::size_t>(sel[static_cast<std::size_t>(c)]));
          B.col(c) << q.x(), q.y(), 1.0;
        }
        b.measure = std::abs(B.determinant());
        if (b.measure > 0) b.inv.topLeftCorner<3, 3>() = B.inverse();
      } else {
        Eigen::Matrix4d B;
        for (int c = 0; c < 4; ++c) {
          const Eigen::Vector3d& q = affine.q(static_cast<std::size_t>(sel[static_cast<std::size_t>(c)]));
          B.col(c) << q.x(), q.y(), q.z(), 1.0;
        }
        b.measure = std::abs(B.determinant());
        if (b.measure > 0) b.inv = B.inverse();
      }
      if (b.measure > 0 && b.inv.allFinite()) all.push_back(b);
      return;
    }
    for (int i = start; i < static_cast<int>(n); ++i) {
      sel[static_cast<std::size_t>(depth)] = i;
      rec(i + 1, depth + 1);
    }
  };
  rec(0, 0);
  std::sort(all.begin(), all.end(), [](const Basis& a, const Basis& b) { return a.measure > b.measure; });
  return all;
}

// The bases tried: the best plus, for each of its points, the best one without that point.
std::vector<const Basis*> ChooseBases(const std::vector<Basis>& all, int max_bases) {
  std::vector<const Basis*> bases = {&all[0]};
  for (int excluded : all[0].idx) {
    for (const Basis& b : all) {
      if (b.measure < 0.05 * all[0].measure) break;
      if (std::find(b.idx.begin(), b.idx.end(), excluded) != b.idx.end()) continue;
      if (std::find(bases.begin(), bases.end(), &b) == bases.end()) bases.push_back(&b);
      break;
    }
    if (static_cast<int>(bases.size()) >= max_bases) break;
  }
  return bases;
}

// Matching of an affine camera's predictions to the detections (nearest pairs first, each used once).
class Matcher {
 public:
  Matcher(const AffineCameraModel& affine, const std::vector<Eigen::Vector2d>& det, std::size_t n,
          const IdentifyOptions& o)
      : affine_(affine), det_(det), n_(n), m_(static_cast<int>(det.size())), o_(o), pred_(n),
        used_(static_cast<std::size_t>(m_)) {}

  bool Match(const Eigen::Matrix<double, 2, 4>& A, Record* r) {
    double min_sep = 1e300;
    for (std::size_t i = 0; i < n_; ++i) pred_[i] = affine_.Predict(A, i);
    for (std::size_t i = 0; i < n_; ++i) {
      for (std::size_t j = i + 1; j < n_; ++j) min_sep = std::min(min_sep, (pred_[i] - pred_[j]).norm());
    }
    if (!(min_sep > 2.0 * o_.tol_min_px)) return false;
    const double tol = std::max(o_.tol_min_px, o_.tol_frac * min_sep);
    pairs_.clear();
    for (std::size_t i = 0; i < n_; ++i) {
      for (int j = 0; j < m_; ++j) {
        const double d = (pred_[i] - det_[static_cast<std::size_t>(j)]).norm();
        if (d < tol) pairs_.emplace_back(d, static_cast<int>(i), j);
      }
    }
    std::sort(pairs_.begin(), pairs_.end());
    r->det_of_model.assign(n_, -1);
    std::fill(used_.begin(), used_.end(), 0);
    r->inliers = 0;
    r->sse = 0;
    for (const auto& [d, i, j] : pairs_) {
      if (r->det_of_model[static_cast<std::size_t>(i)] >= 0 || used_[static_cast<std::size_t>(j)]) continue;
      r->det_of_model[static_cast<std::size_t>(i)] = j;
      used_[static_cast<std::size_t>(j)] = 1;
      ++r->inliers;
      r->sse += d * d;
    }
    r->tol = tol;
    r->A = A;
    return true;
  }

 private:
  const AffineCameraModel& affine_;
  const std::vector<Eigen::Vector2d>& det_;
  const std::size_t n_;
  const int m_;
  const IdentifyOptions& o_;
  std::vector<Eigen::Vector2d> pred_;
  std::vector<std::tuple<double, int, int>> pairs_;
  std::vector<char> used_;
};

// The best few distinct assignments.
class TopRecords {
 public:
  void Keep(const Record& r) {
    for (Record& t : top_) {
      if (t.det_of_model == r.det_of_model) {
        if (Better(r, t)) t = r;
        return;
      }
    }
    if (top_.size() < kKeep || Better(r, top_.back())) {
      top_.push_back(r);
      std::sort(top_.begin(), top_.end(), Better);
      if (top_.size() > kKeep) top_.pop_back();
    }
  }
  const std::vector<Record>& records() const { return top_; }

 private:
  static constexpr std::size_t kKeep = 8;
  std::vector<Record> top_;
};

// Every hypothesis: each basis against each ordered k-tuple of distinct detections; counts them.
void TryHypotheses(const std::vector<const Basis*>& bases, const std::vector<Eigen::Vector2d>& det, int k,
                   bool planar, const IdentifyOptions& o, Matcher* matcher, TopRecords* top, long* hypotheses) {
  const int m = static_cast<int>(det.size());
  Eigen::Matrix<double, 2, 4> X = Eigen::Matrix<double, 2, 4>::Zero();
  std::vector<int> tuple(static_cast<std::size_t>(k));
  Record r;
  for (const Basis* b : bases) {
    std::function<void(int)> loop = [&](int depth) {
      if (depth == k) {
        for (int c = 0; c < k; ++c) X.col(c) = det[static_cast<std::size_t>(tuple[static_cast<std::size_t>(c)])];
        Eigen::Matrix<double, 2, 4> A = Eigen::Matrix<double, 2, 4>::Zero();
        if (planar) {
          const Eigen::Matrix<double, 2, 3> Ak = X.leftCols<3>() * b->inv.topLeftCorner<3, 3>();
          A.col(0) = Ak.col(0);
          A.col(1) = Ak.col(1);
          A.col(3) = Ak.col(2);
        } else {
          A = X * b->inv;
          const Eigen::Vector3d r0 = A.block<1, 3>(0, 0).transpose(), r1 = A.block<1, 3>(1, 0).transpose();
          const double n0 = r0.norm(), n1 = r1.norm();
          if (!(n0 > 0 && n1 > 0)) return;
          if (std::max(n0, n1) > o.max_aspect * std::min(n0, n1)) return;
          if (std::abs(r0.dot(r1)) > o.max_skew_cos * n0 * n1) return;
        }
        ++*hypotheses;
        if (matcher->Match(A, &r)) top->Keep(r);
        return;
      }
      for (int j = 0; j < m; ++j) {
        bool dup = false;
        for (int c = 0; c < depth; ++c) dup |= tuple[static_cast<std::size_t>(c)] == j;
        if (dup) continue;
        tuple[static_cast<std::size_t>(depth)] = j;
        loop(depth + 1);
      }
    };
    loop(0);
  }
}

// The leading assignments refined by least squares and re-matched (twice), distinct, best first.
std::vector<Record> Refine(const std::vector<Record>& top, const std::vector<Eigen::Vector2d>& det, std::size_t n,
                           const AffineCameraModel& affine, Matcher* matcher) {
  std::vector<Record> refined;
  for (const Record& t : top) {
    Record cur = t;
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<int> idx;
      std::vector<Eigen::Vector2d> px;
      for (std::size_t i = 0; i < n; ++i) {
        if (cur.det_of_model[i] >= 0) {
          idx.push_back(static_cast<int>(i));
          px.push_back(det[static_cast<std::size_t>(cur.det_of_model[i])]);
        }
      }
      Eigen::Matrix<double, 2, 4> A;
      if (!affine.Fit(idx, px, &A)) break;
      Record next;
      if (!matcher->Match(A, &next)) break;
      cur = next;
    }
    cur.rms = cur.inliers > 0 ? std::sqrt(cur.sse / cur.inliers) : 0.0;
    bool dup = false;
    for (const Record& q : refined) dup |= q.det_of_model == cur.det_of_model;
    if (!dup) refined.push_back(cur);
  }
  std::sort(refined.begin(), refined.end(), Better);
  return refined;
}

}  // namespace

const io::OptionTable<IdentifyOptions>& IdentifyOptions::Table() {
  using B = io::Bounds;
  using O = IdentifyOptions;
  static const io::OptionTable<O> table =
      io::OptionTable<O>()
          .Integer("--min-identified", &O::min_identified, "", B::AtLeast(4),
                   "Markers an identification must explain (>= 5 non-planar, >= 4 planar targets)")
          .Real("--id-tolerance", &O::tol_frac, "", B::LeftOpen(0, 0.5),
                "Identification: a marker matches a prediction within this fraction of the smallest separation")
          .Real("--ambiguity-ratio", &O::ambiguity_ratio, "", B::AtLeast(1),
                "Identification refused when a different assignment fits within this factor of the best RMS");
  return table;
}

bool IdentifyOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  auto fail = [&](const char* w) {
    *why = w;
    return false;
  };
  if (!(tol_min_px > 0)) return fail("identification tolerance must be > 0 px");
  if (!(max_aspect > 1) || !(max_skew_cos > 0 && max_skew_cos <= 1)) return fail("bad weak-perspective limits");
  if (!(planar_ratio >= 0 && planar_ratio < 1)) return fail("planar ratio must be in [0, 1)");
  if (max_bases < 1 || max_detections < 4) return fail("need at least 1 basis and 4 detections");
  return true;
}

AffineCameraModel::AffineCameraModel(const target::FeatureModel& model, double planar_ratio) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : model.p_body) c += p;
  c /= static_cast<double>(std::max<std::size_t>(1, model.size()));
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (const auto& p : model.p_body) S += (p - c) * (p - c).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(S);
  Eigen::Matrix3d E;
  for (int k = 0; k < 3; ++k) E.col(k) = es.eigenvectors().col(2 - k);
  const double l1 = es.eigenvalues()(2), l3 = std::max(0.0, es.eigenvalues()(0));
  planar_ = !(l1 > 0) || l3 < planar_ratio * l1;
  for (const auto& p : model.p_body) {
    Eigen::Vector3d q = E.transpose() * (p - c);
    if (planar_) q.z() = 0.0;
    q_.push_back(q);
  }
}

Eigen::Vector2d AffineCameraModel::Predict(const Eigen::Matrix<double, 2, 4>& A, std::size_t i) const {
  return A.leftCols<3>() * q_[i] + A.col(3);
}

bool AffineCameraModel::Fit(const std::vector<int>& idx, const std::vector<Eigen::Vector2d>& px,
                            Eigen::Matrix<double, 2, 4>* A) const {
  const int cols = planar_ ? 3 : 4;
  const int n = static_cast<int>(idx.size());
  if (n < cols) return false;
  Eigen::MatrixXd Q(n, cols);
  Eigen::MatrixXd X(n, 2);
  for (int r = 0; r < n; ++r) {
    const Eigen::Vector3d& q = q_[static_cast<std::size_t>(idx[static_cast<std::size_t>(r)])];
    if (planar_) {
      Q.row(r) << q.x(), q.y(), 1.0;
    } else {
      Q.row(r) << q.x(), q.y(), q.z(), 1.0;
    }
    X.row(r) = px[static_cast<std::size_t>(r)].transpose();
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Q);
  if (qr.rank() < cols) return false;
  const Eigen::MatrixXd sol = qr.solve(X);  // cols × 2
  A->setZero();
  if (planar_) {
    A->col(0) = sol.row(0).transpose();
    A->col(1) = sol.row(1).transpose();
    A->col(3) = sol.row(2).transpose();
  } else {
    for (int k = 0; k < 4; ++k) A->col(k) = sol.row(k).transpose();
  }
  return A->allFinite();
}

Identification Identify(const std::vector<Eigen::Vector2d>& all_detections, const target::FeatureModel& model,
                        const AffineCameraModel& affine, const IdentifyOptions& o) {
  Identification out;
  const std::size_t n = model.size();
  out.detection_of_model.assign(n, -1);
  const bool planar = affine.planar();
  const int k = planar ? 3 : 4;
  const int min_id = std::max(o.min_identified, planar ? 4 : 5);
  std::vector<Eigen::Vector2d> det(all_detections.begin(),
                                   all_detections.begin() +
                                       static_cast<std::ptrdiff_t>(std::min<std::size_t>(
                                           all_detections.size(), static_cast<std::size_t>(o.max_detections))));
  const int m = static_cast<int>(det.size());
  if (m < min_id || static_cast<int>(n) < min_id) {
    out.why = "only " + std::to_string(m) + " marker candidates (" + std::to_string(min_id) + " needed to identify)";
    return out;
  }

  // Bases: k-subsets of model points by volume (area), the best plus, for each of its points,
  // the best one without that point.
  const std::vector<Basis> all = AllBases(affine, n, k);
  if (all.empty()) {
    out.why = "the target model has no well-conditioned basis";
    return out;
  }
  const std::vector<const Basis*> bases = ChooseBases(all, o.max_bases);

  Matcher matcher(affine, det, n, o);
  TopRecords top_records;
  TryHypotheses(bases, det, k, planar, o, &matcher, &top_records, &out.hypotheses);
  const std::vector<Record>& top = top_records.records();
  if (top.empty() || top.front().inliers < min_id) {
    out.why = "no consistent identification (best: " + std::to_string(top.empty() ? 0 : top.front().inliers) + " of " +
              std::to_string(n) + " markers, " + std::to_string(min_id) + " needed)";
    return out;
  }

  // Refine the leading assignments by least squares, re-match, and look for a rival.
  const std::vector<Record> refined = Refine(top, det, n, affine, &matcher);
  const Record& best = refined.front();
  out.identified = best.inliers;
  out.rms_px = best.rms;
  out.tol_px = best.tol;
  out.A = best.A;
  if (best.inliers < min_id) {
    out.why = "no consistent identification (" + std::to_string(best.inliers) + " markers, " + std::to_string(min_id) +
              " needed)";
    return out;
  }
  for (std::size_t i = 1; i < refined.size(); ++i) {
    const Record& rival = refined[i];
    if (rival.inliers == best.inliers && rival.rms < o.ambiguity_ratio * best.rms + 0.5) {
      out.ambiguous = true;
      out.why = "ambiguous identification: two assignments of " + std::to_string(best.inliers) +
                " markers fit equally well (RMS " + std::to_string(best.rms) + " and " + std::to_string(rival.rms) +
                " px); is the marker layout symmetric?";
      return out;
    }
  }
  out.detection_of_model = best.det_of_model;
  out.ok = true;
  return out;
}

}  // namespace rk::extract
