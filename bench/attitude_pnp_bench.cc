// Accuracy and speed of the rk-attitude oi solver (pose/pnp.h: weak-perspective start →
// orthogonal iteration → reprojection polish) against OpenCV 4.6 on the same random problems
// (sim/attitude_problems.h). Issue 4 target: over 10 000 problems (0.1–1 px noise, 4–12
// points), rotation and translation errors within 2 % of the best OpenCV method
// (SOLVEPNP_SQPNP refined with solvePnPRefineLM), and at least as fast.
//
//   attitude_pnp_bench [--problems N] [--geometry box|planar|narrow|narrow-planar|all]
//                      [--seed S] [--repeats R] [--methods LIST]
//
// Per method: rotation error = angle of R_est·R_trueᵀ (deg), translation error =
// ‖t_est − t_true‖ / ‖t_true‖ (%), mean / median / 95th percentile / max, and the number of
// gross failures (rotation error > 5°, or no solution). Time per problem: wall time of a loop
// over all problems (inputs prepared beforehand, the same for every method), best of R repeats,
// methods interleaved so that machine load affects them alike. Methods:
//   oi          rk-attitude oi's solver, default options (second start auto)
//   oi-pure     orthogonal iteration only (no polish, no second start)
//   oi-always   default solver with the second start always run
//   oi-handoff=T  default solver with OI handing over to the polish at ‖ΔR‖ < T
//   sqpnp-lm    cv::solvePnP(SOLVEPNP_SQPNP) + cv::solvePnPRefineLM   (the reference)
//   sqpnp       cv::solvePnP(SOLVEPNP_SQPNP)
//   iterative   cv::solvePnP(SOLVEPNP_ITERATIVE)
//   epnp-lm     cv::solvePnP(SOLVEPNP_EPNP) + cv::solvePnPRefineLM
//   ippe-lm     cv::solvePnP(SOLVEPNP_IPPE) + cv::solvePnPRefineLM (planar geometries only)
//   none        does nothing: the harness's own cost, to subtract from callgrind instruction counts
// Instruction counts, immune to machine load (docs/benchmarks.md):
//   valgrind --tool=callgrind --callgrind-out-file=/dev/null build/bench/attitude_pnp_bench
//       --problems 1000 --repeats 1 --geometry box --methods oi      (then sqpnp-lm, then none)
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "geo/angles.h"
#include "io/csv.h"
#include "pose/pnp.h"
#include "sim/attitude_problems.h"

namespace {

using rk::sim::PnpGeometry;
using rk::sim::PnpProblem;

struct Estimate {
  bool ok = false;
  int oi_iterations = 0, refine_iterations = 0, starts = 0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

struct Prepared {
  PnpProblem pb;
  std::vector<Eigen::Vector2d> xn;   // normalised
  std::vector<cv::Point3d> obj;      // for OpenCV
  std::vector<cv::Point2d> img;
  cv::Mat K;
};

using Method = std::function<Estimate(const Prepared&)>;

Estimate FromCv(bool ok, const cv::Mat& rvec, const cv::Mat& tvec) {
  Estimate e;
  e.ok = ok && !rvec.empty() && !tvec.empty();
  if (!e.ok) return e;
  cv::Mat Rm;
  cv::Rodrigues(rvec, Rm);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) e.R(r, c) = Rm.at<double>(r, c);
    e.t(r) = tvec.at<double>(r);
  }
  e.ok = e.R.allFinite() && e.t.allFinite();
  return e;
}

Method CvMethod(int flag, bool refine) {
  return [flag, refine](const Prepared& p) {
    cv::Mat rvec, tvec;
    bool ok = false;
    try {
      ok = cv::solvePnP(p.obj, p.img, p.K, cv::noArray(), rvec, tvec, false, flag);
      if (ok && refine) cv::solvePnPRefineLM(p.obj, p.img, p.K, cv::noArray(), rvec, tvec);
    } catch (const cv::Exception&) {
      ok = false;
    }
    return FromCv(ok, rvec, tvec);
  };
}

Method OiMethod(rk::pose::PnpOptions opt) {
  auto solver = std::make_shared<rk::pose::PnpSolver>(opt);
  return [solver](const Prepared& p) {
    const rk::pose::PnpResult r = solver->Solve(p.xn, p.pb.p_body, {}, p.pb.fx, p.pb.fy);
    Estimate e;
    e.ok = r.ok;
    e.R = r.best.R_cam_body;
    e.t = r.best.t_cam;
    e.oi_iterations = r.best.oi_iterations + (r.has_alt ? r.alt.oi_iterations : 0);
    e.refine_iterations = r.best.refine_iterations + (r.has_alt ? r.alt.refine_iterations : 0);
    e.starts = r.second_start_run ? 2 : 1;
    return e;
  };
}

struct Stats {
  double mean = 0, median = 0, p95 = 0, max = 0;
};
Stats Summarise(std::vector<double> v) {
  Stats s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / static_cast<double>(v.size());
  s.median = v[v.size() / 2];
  s.p95 = v[static_cast<std::size_t>(0.95 * static_cast<double>(v.size() - 1))];
  s.max = v.back();
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  int problems = 10000, repeats = 3;
  std::uint64_t seed = 1;
  std::string geometry = "all";
  std::string methods_arg = "oi,oi-pure,oi-always,sqpnp-lm,sqpnp,iterative,epnp-lm,ippe-lm";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "attitude_pnp_bench: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--problems") {
      problems = std::atoi(next().c_str());
    } else if (a == "--geometry") {
      geometry = next();
    } else if (a == "--seed") {
      seed = std::strtoull(next().c_str(), nullptr, 10);
    } else if (a == "--repeats") {
      repeats = std::atoi(next().c_str());
    } else if (a == "--methods") {
      methods_arg = next();
    } else {
      std::fprintf(stderr, "usage: attitude_pnp_bench [--problems N] [--geometry G|all] [--seed S] [--repeats R] "
                           "[--methods LIST]\n");
      return 2;
    }
  }
  std::vector<std::string> geometries;
  if (geometry == "all") {
    geometries = {"box", "planar", "narrow", "narrow-planar"};
  } else {
    geometries = {geometry};
  }
  const std::vector<std::string> method_names = rk::io::SplitList(methods_arg);

  std::printf("# attitude_pnp_bench: %d problems per geometry, 4-12 points, noise 0.1-1 px, seed %llu\n", problems,
              static_cast<unsigned long long>(seed));
  std::printf("%-14s %-10s %6s | %9s %9s %9s %9s | %9s %9s %9s | %8s %9s\n", "geometry", "method", "fails",
              "rot_mean", "rot_med", "rot_p95", "rot_max", "t_mean%", "t_med%", "t_p95%", "us/prob", "ratio");
  for (const std::string& gname : geometries) {
    rk::sim::PnpProblemOptions po;
    if (!rk::sim::ParsePnpGeometry(gname, &po.geometry)) {
      std::fprintf(stderr, "unknown geometry %s\n", gname.c_str());
      return 2;
    }
    po.seed = seed;
    const bool planar = po.geometry == PnpGeometry::kPlanar || po.geometry == PnpGeometry::kNarrowPlanar;
    std::vector<Prepared> prep(static_cast<std::size_t>(problems));
    for (int k = 0; k < problems; ++k) {
      Prepared& p = prep[static_cast<std::size_t>(k)];
      p.pb = rk::sim::MakePnpProblem(po, static_cast<std::uint64_t>(k));
      for (std::size_t i = 0; i < p.pb.px.size(); ++i) {
        p.xn.emplace_back((p.pb.px[i].x() - p.pb.cx) / p.pb.fx, (p.pb.px[i].y() - p.pb.cy) / p.pb.fy);
        p.obj.emplace_back(p.pb.p_body[i].x(), p.pb.p_body[i].y(), p.pb.p_body[i].z());
        p.img.emplace_back(p.pb.px[i].x(), p.pb.px[i].y());
      }
      p.K = (cv::Mat_<double>(3, 3) << p.pb.fx, 0, p.pb.cx, 0, p.pb.fy, p.pb.cy, 0, 0, 1);
    }
    struct Entry {
      std::string name;
      Method m;
      std::vector<Estimate> est;
      double best_s = 1e300;
    };
    std::vector<Entry> entries;
    for (const std::string& mn : method_names) {
      Entry e;
      e.name = mn;
      rk::pose::PnpOptions opt;
      if (mn == "oi") {
        e.m = OiMethod(opt);
      } else if (mn == "oi-pure") {
        opt.polish = false;
        opt.second_start = rk::pose::SecondStart::kNever;
        e.m = OiMethod(opt);
      } else if (mn.rfind("oi-handoff=", 0) == 0) {  // e.g. oi-handoff=1e-4: OI hand-over tolerance
        opt.oi_handoff_tol = std::atof(mn.c_str() + 11);
        e.m = OiMethod(opt);
      } else if (mn == "oi-always") {
        opt.second_start = rk::pose::SecondStart::kAlways;
        e.m = OiMethod(opt);
      } else if (mn == "none") {  // harness only: for instruction counts (callgrind) of the others
        e.m = [](const Prepared&) { return Estimate{}; };
      } else if (mn == "sqpnp-lm") {
        e.m = CvMethod(cv::SOLVEPNP_SQPNP, true);
      } else if (mn == "sqpnp") {
        e.m = CvMethod(cv::SOLVEPNP_SQPNP, false);
      } else if (mn == "iterative") {
        e.m = CvMethod(cv::SOLVEPNP_ITERATIVE, false);
      } else if (mn == "epnp-lm") {
        e.m = CvMethod(cv::SOLVEPNP_EPNP, true);
      } else if (mn == "ippe-lm") {
        if (!planar) continue;
        e.m = CvMethod(cv::SOLVEPNP_IPPE, true);
      } else {
        std::fprintf(stderr, "unknown method %s\n", mn.c_str());
        return 2;
      }
      e.est.resize(prep.size());
      entries.push_back(std::move(e));
    }
    for (int rep = 0; rep < repeats; ++rep) {
      for (Entry& e : entries) {
        const auto t0 = std::chrono::steady_clock::now();
        for (std::size_t k = 0; k < prep.size(); ++k) e.est[k] = e.m(prep[k]);
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        e.best_s = std::min(e.best_s, s);
      }
    }
    double ref_s = 0;
    for (const Entry& e : entries) {
      if (e.name == "sqpnp-lm") ref_s = e.best_s;
    }
    for (const Entry& e : entries) {
      std::vector<double> rot, tr;
      int fails = 0;
      double oi_it = 0, ref_it = 0, starts = 0;
      for (std::size_t k = 0; k < prep.size(); ++k) {
        const Estimate& es = e.est[k];
        const PnpProblem& pb = prep[k].pb;
        oi_it += es.oi_iterations;
        ref_it += es.refine_iterations;
        starts += es.starts;
        if (!es.ok) {
          ++fails;
          continue;
        }
        const double r = rk::geo::RadToDeg(rk::pose::RotationAngle(es.R, pb.R_cam_body));
        if (r > 5.0) ++fails;
        rot.push_back(r);
        tr.push_back(100.0 * (es.t - pb.t_cam).norm() / pb.t_cam.norm());
      }
      const Stats sr = Summarise(rot), st = Summarise(tr);
      std::printf("%-14s %-10s %6d | %9.5f %9.5f %9.5f %9.3f | %9.5g %9.5f %9.5f | %8.2f %9.3f\n", gname.c_str(),
                  e.name.c_str(), fails, sr.mean, sr.median, sr.p95, sr.max, st.mean, st.median, st.p95,
                  1e6 * e.best_s / static_cast<double>(prep.size()), ref_s > 0 ? e.best_s / ref_s : 0.0);
      if (starts > 0) {
        const double np = static_cast<double>(prep.size());
        std::printf("%-14s %-10s        per problem: %.2f starts, %.1f OI iterations, %.1f LM iterations\n", "",
                    e.name.c_str(), starts / np, oi_it / np, ref_it / np);
      }
    }
    std::fflush(stdout);
  }
  return 0;
}
