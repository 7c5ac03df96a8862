// rk-attitude cylinder per-frame pipeline: points file, theodolite interpolation, statuses, continuity.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <sstream>
#include <vector>

#include "attitude/cylinder_run.h"
#include "geo/angles.h"
#include "io/csv.h"
#include "io/error.h"
#include "sim/theodolite_render.h"
#include "sim/theodolite_scene.h"

namespace rk::attitude {
namespace {

using geo::DegToRad;
using geo::RadToDeg;

// Points written with 6 decimals (1e-6 px) and a cubic-interpolated theodolite log at 50 Hz: the attitude of
// exact data is reproduced to ~1e-5°; 1e-4° leaves room.
constexpr double kExactDeg = 1e-4;

struct Trial {
  sim::TheodoliteSimulator sim;
  CylinderPointsFile points;
  formats::TurretLog theo;
  target::CylinderShape shape;
};

std::string PointsCsv(const sim::TheodoliteSimulator& sim) {
  std::ostringstream s;
  s.precision(12);
  s << "frame,t_s,id,x_px,y_px\n";
  const char* ids[3] = {"nose", "tail1", "tail2"};
  for (const auto& f : sim.frames())
    for (int i = 0; i < 3; ++i)
      s << f.frame << "," << f.t_s << "," << ids[i] << "," << f.measured_px[static_cast<std::size_t>(i)].x() << ","
        << f.measured_px[static_cast<std::size_t>(i)].y() << "\n";
  return s.str();
}

formats::TurretLog TheoLog(const sim::TheodoliteSimulator& sim) {
  formats::TurretLog log;
  log.source = "theo.csv";
  for (const auto& s : sim.TheodoliteLog()) {
    log.t_s.push_back(s.t_s);
    log.az_rad.push_back(s.az_rad);
    log.el_rad.push_back(s.el_rad);
  }
  return log;
}

Trial MakeTrial(sim::TheodoliteSimOptions o) {
  sim::TheodoliteSimulator sim(o);
  CylinderPointsFile pts = ReadCylinderPoints(io::CsvTable::Parse(PointsCsv(sim), "points.csv"));
  formats::TurretLog theo = TheoLog(sim);
  return Trial{std::move(sim), std::move(pts), std::move(theo), o.shape};
}

TEST(CylinderRun, ExactPointsGiveTheTruthAndTheMirror) {
  sim::TheodoliteSimOptions o;
  o.duration_s = 1.0;
  o.speed_mps = 80.0;
  const Trial t = MakeTrial(o);
  const CylinderRunResult r = RunCylinder(t.points, t.theo, t.sim.options().camera, t.shape, CylinderRunOptions{});
  ASSERT_EQ(r.rows.size(), t.sim.frames().size());
  for (std::size_t k = 0; k < r.rows.size(); ++k) {
    const CylinderRow& row = r.rows[k];
    const sim::TheodoliteFrameTruth& f = t.sim.frames()[k];
    ASSERT_EQ(row.status, RowStatus::kOk) << k;
    EXPECT_NEAR(geo::WrapDeg180(RadToDeg(*row.yaw_rad - f.pose.yaw_rad)), 0.0, kExactDeg);
    EXPECT_NEAR(RadToDeg(*row.pitch_rad - f.pose.pitch_rad), 0.0, kExactDeg);
    EXPECT_NEAR(geo::WrapDeg180(RadToDeg(*row.alt_yaw_rad - *f.alt_yaw_rad)), 0.0, kExactDeg);
    EXPECT_NEAR((*row.range_m)(0), f.points.nose.norm(), 1e-3);
    ASSERT_TRUE(row.sigma_yaw_rad.has_value());
    // First row: no history, two solutions → the SPEC.md §3 default (nose-nearer, the truth at view > 90°).
    EXPECT_EQ(row.solution, k == 0 ? CylinderSolutionStatus::kAmbiguous : CylinderSolutionStatus::kContinuity);
  }
  const std::string csv = CylinderCsv(r).str();
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "frame,t_s,yaw_deg,pitch_deg,status,alt_yaw_deg,alt_pitch_deg,solution,range_nose_m,range_tail1_m,"
            "range_tail2_m,sigma_yaw_deg,sigma_pitch_deg,separation_deg,asymmetry_px,edge_tilt_deg,"
            "boresight_az_deg,boresight_el_deg");
}

// A target whose view passes through side-on (the two solutions touch and swap which is nose-nearer): the
// primary stays on the true branch by continuity, where the paper's "nearer first" would jump to the mirror.
TEST(CylinderRun, ContinuityThroughTheSideOnView) {
  sim::TheodoliteSimOptions o;
  o.el_deg = 30.0;  // view ≈ 89.5° at mid-trial; climbing at 300 m/s sweeps it from ~105° to ~80°
  o.speed_mps = 300.0;
  o.duration_s = 2.0;
  const Trial t = MakeTrial(o);
  ASSERT_GT(t.sim.frames().front().view_angle_rad, M_PI / 2);
  ASSERT_LT(t.sim.frames().back().view_angle_rad, M_PI / 2);
  const CylinderRunResult r = RunCylinder(t.points, t.theo, t.sim.options().camera, t.shape, CylinderRunOptions{});
  int side_on = 0;
  for (std::size_t k = 0; k < r.rows.size(); ++k) {
    const CylinderRow& row = r.rows[k];
    if (row.solution == CylinderSolutionStatus::kSideOn) ++side_on;
    const double err = RadToDeg(AxisAngle(*row.axis_enu, t.sim.frames()[k].pose.Axis()));
    // Near the double root the two solutions are within --ambiguity-deg of each other (and exact data).
    EXPECT_LT(err, row.solution == CylinderSolutionStatus::kSideOn ? 1.0 : kExactDeg) << "frame " << k;
  }
  EXPECT_GT(side_on, 0);
  // The first frame (view > 90°, no history): the SPEC.md §3 default (nose-nearer), flagged ambiguous.
  EXPECT_EQ(r.rows.front().solution, CylinderSolutionStatus::kAmbiguous);
  // The last frames are nose-farther (view < 90°): a single-frame solve would take the nose-nearer mirror;
  // continuity keeps the truth (checked in the loop above).
  EXPECT_EQ(r.rows.back().solution, CylinderSolutionStatus::kContinuity);
}

// Issue 20, the image fit's cost: both solutions are fitted only where history cannot choose (the first row:
// ambiguous) or they are within --fit-both-within-deg, one where continuity chooses; every fit after the first converged one starts warm; the fitted
// rows stay within the image fit's tolerance of the truth. With --fit-time-limit spent after the first row, the
// other rows keep the three-point solution (no fit) and are counted.
TEST(CylinderRun, ImageFitOnlyTheChosenSolutionWarmStarted) {
  sim::TheodoliteSimOptions o;
  o.camera.width_px = o.camera.height_px = 640;
  o.camera.principal_point_px = {319.5, 319.5};
  o.speed_mps = 50.0;
  o.track_error_px = 10.0;
  o.duration_s = 0.3;  // 7 frames
  const Trial t = MakeTrial(o);
  sim::SilhouetteRenderOptions ro;
  std::mt19937_64 rng(5);
  std::vector<cv::Mat> frames;
  for (const auto& f : t.sim.frames()) frames.push_back(sim::RenderSilhouetteFrame(o.camera, f, o.shape, ro, rng));
  const CylinderFrameReader reader = [&](std::int64_t frame) -> const cv::Mat& {
    return frames.at(static_cast<std::size_t>(frame));
  };
  const CylinderRunResult r = RunCylinder(t.points, t.theo, o.camera, t.shape, CylinderRunOptions{}, &reader);
  std::size_t two = 0, one = 0;
  for (std::size_t k = 0; k < r.rows.size(); ++k) {
    const CylinderRow& row = r.rows[k];
    ASSERT_TRUE(row.fit.has_value()) << k;
    ASSERT_EQ(*row.fit, CylinderImageFitStatus::kConverged) << k;
    const bool both = row.solution == CylinderSolutionStatus::kAmbiguous ||
                      row.solution == CylinderSolutionStatus::kSideOn ||
                      (row.separation_rad && RadToDeg(*row.separation_rad) < CylinderRunOptions{}.fit_both_within_deg);
    (both ? two : one) += 1;
    // The fit's tolerance on a 640-px crop of seed 004 (test_cylinder_image_fit.cc: 4σ of one frame).
    EXPECT_LT(RadToDeg(AxisAngle(*row.axis_enu, t.sim.frames()[k].pose.Axis())), 0.25) << k;
  }
  EXPECT_EQ(r.rows.front().solution, CylinderSolutionStatus::kAmbiguous);
  EXPECT_GT(one, 0u);
  EXPECT_EQ(r.fits, 2 * two + one);
  EXPECT_EQ(r.fits_warm, r.fits - 1);
  EXPECT_EQ(r.rows_fit_time_limit, 0u);

  CylinderRunOptions limited;
  limited.fit_time_limit_s = 1e-9;
  const CylinderRunResult l = RunCylinder(t.points, t.theo, o.camera, t.shape, limited, &reader);
  EXPECT_EQ(l.rows_fit_time_limit, l.rows.size() - 1);
  EXPECT_TRUE(l.rows.front().fit.has_value());
  EXPECT_FALSE(l.rows.back().fit.has_value());
  EXPECT_EQ(l.SummaryJson()["image_fit"]["rows_not_fitted_time_limit"], l.rows.size() - 1);
}

TEST(CylinderRun, YawThroughNorthStaysContinuous) {
  sim::TheodoliteSimOptions o;
  o.az_deg = 150.0;  // view ≈ 138°: far from side-on, the two solutions well apart
  o.el_deg = 10.0;
  o.yaw_deg = 0.0;
  o.pitch_deg = 20.0;
  o.yaw_rate_deg_s = 4.0;  // 358° → 2° over the trial
  o.duration_s = 1.0;
  const Trial t = MakeTrial(o);
  const CylinderRunResult r = RunCylinder(t.points, t.theo, t.sim.options().camera, t.shape, CylinderRunOptions{});
  bool low = false, high = false;
  for (std::size_t k = 0; k < r.rows.size(); ++k) {
    ASSERT_TRUE(r.rows[k].yaw_rad.has_value());
    const double y = RadToDeg(*r.rows[k].yaw_rad);
    EXPECT_GE(y, 0.0);
    EXPECT_LT(y, 360.0);
    low = low || y < 5.0;
    high = high || y > 355.0;
    EXPECT_NEAR(geo::WrapDeg180(y - RadToDeg(t.sim.frames()[k].pose.yaw_rad)), 0.0, kExactDeg);
  }
  EXPECT_TRUE(low && high);
}

TEST(CylinderRun, StatusesForBadRows) {
  sim::TheodoliteSimOptions o;
  o.duration_s = 1.0;
  sim::TheodoliteSimulator sim(o);
  std::string csv = PointsCsv(sim);
  const camera::CameraModel& cam = o.camera;
  // Frame 2: tail2 missing. Frame 3: nose outside the image. Frame 4: nose and tail1 swapped (inconsistent).
  // Frame 5: tail chase (nose on the tail centre). Frame 6: tail1 = tail2 (degenerate). Frame 7: the three
  // points collinear with the nose beyond tail2 (inconsistent with a cylinder).
  std::istringstream in(csv);
  std::ostringstream out;
  std::string line;
  std::getline(in, line);
  out << line << "\n";
  std::map<std::pair<int, std::string>, Eigen::Vector2d> px;
  for (const auto& f : sim.frames()) {
    px[{static_cast<int>(f.frame), "nose"}] = f.nose_px;
    px[{static_cast<int>(f.frame), "tail1"}] = f.tail1_px;
    px[{static_cast<int>(f.frame), "tail2"}] = f.tail2_px;
  }
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string fr, t, id;
    std::getline(ls, fr, ',');
    std::getline(ls, t, ',');
    std::getline(ls, id, ',');
    const int k = std::stoi(fr);
    Eigen::Vector2d p = px[{k, id}];
    if (k == 2 && id == "tail2") continue;
    if (k == 3 && id == "nose") p = Eigen::Vector2d(cam.width_px + 5.0, 10.0);
    if (k == 4 && id == "nose") p = px[{k, "tail1"}];
    if (k == 4 && id == "tail1") p = px[{k, "nose"}];
    if (k == 5 && id == "nose") p = 0.5 * (px[{k, "tail1"}] + px[{k, "tail2"}]) + Eigen::Vector2d(0.3, -0.2);
    if (k == 6 && id == "tail2") p = px[{k, "tail1"}];
    if (k == 7 && id == "nose") p = px[{k, "tail2"}] + 5.0 * (px[{k, "tail2"}] - px[{k, "tail1"}]);  // collinear
    out.precision(12);
    out << fr << "," << t << "," << id << "," << p.x() << "," << p.y() << "\n";
  }
  const CylinderPointsFile pts = ReadCylinderPoints(io::CsvTable::Parse(out.str(), "points.csv"));
  formats::TurretLog theo = TheoLog(sim);
  // A theodolite gap of 0.24 s (> the 0.2 s limit) around frame 15: drop the log samples within ±0.11 s.
  formats::TurretLog gap;
  gap.source = theo.source;
  const double t15 = sim.frames()[15].t_s;
  for (std::size_t i = 0; i < theo.t_s.size(); ++i) {
    if (std::abs(theo.t_s[i] - t15) < 0.11) continue;
    gap.t_s.push_back(theo.t_s[i]);
    gap.az_rad.push_back(theo.az_rad[i]);
    gap.el_rad.push_back(theo.el_rad[i]);
  }
  const CylinderRunResult r = RunCylinder(pts, gap, cam, o.shape,
                                          CylinderRunOptions{});
  using S = CylinderSolutionStatus;
  EXPECT_EQ(r.rows[2].status, RowStatus::kLost);
  EXPECT_EQ(r.rows[2].solution, S::kMissingPoints);
  EXPECT_EQ(r.rows[3].status, RowStatus::kInvalid);
  EXPECT_EQ(r.rows[3].solution, S::kOutsideImage);
  EXPECT_EQ(r.rows[4].solution, S::kInconsistent);
  EXPECT_EQ(r.rows[5].status, RowStatus::kOk);
  EXPECT_EQ(r.rows[5].solution, S::kTailChase);
  EXPECT_EQ(r.rows[6].solution, S::kDegenerate);
  EXPECT_EQ(r.rows[7].solution, S::kInconsistent);
  EXPECT_EQ(r.rows[7].status, RowStatus::kInvalid);
  EXPECT_EQ(r.rows[15].solution, S::kNoTheodolite);
  EXPECT_EQ(r.rows[15].status, RowStatus::kInvalid);
  EXPECT_EQ(r.rows[10].status, RowStatus::kOk);
  // Invalid rows carry no attitude in the file.
  const io::CsvTable out_csv = io::CsvTable::Parse(CylinderCsv(r).str(), "axis.csv");
  const int c_yaw = out_csv.RequireColumn("yaw_deg");
  EXPECT_TRUE(out_csv.IsEmpty(3, c_yaw));
  EXPECT_TRUE(out_csv.IsEmpty(15, c_yaw));
  EXPECT_FALSE(out_csv.IsEmpty(10, c_yaw));
}

TEST(CylinderRun, NoCoverageAndNoPointsAreErrors) {
  sim::TheodoliteSimOptions o;
  o.duration_s = 0.2;
  const Trial t = MakeTrial(o);
  formats::TurretLog late = t.theo;
  for (double& x : late.t_s) x += 100.0;
  try {
    RunCylinder(t.points, late, t.sim.options().camera, t.shape, CylinderRunOptions{});
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidData);
    EXPECT_NE(std::string(e.what()).find("theo.csv"), std::string::npos);
  }
  const CylinderPointsFile only_nose =
      ReadCylinderPoints(io::CsvTable::Parse("frame,t_s,id,x_px,y_px\n0,1.0,nose,700,700\n", "p.csv"));
  try {
    RunCylinder(only_nose, t.theo, t.sim.options().camera, t.shape, CylinderRunOptions{});
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kProcessing);
  }
}

TEST(CylinderPoints, ReaderErrorsNameLineAndColumn) {
  auto expect = [](const char* text, const char* where, const char* what) {
    try {
      ReadCylinderPoints(io::CsvTable::Parse(text, "p.csv"));
      ADD_FAILURE() << text;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::kInvalidData);
      EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  expect("frame,t_s,id,x_px,y_px\n0,1.0,nose,1,2\n0,1.0,fin,3,4\n", "p.csv:3:", "unknown point id 'fin'");
  expect("frame,t_s,id,x_px,y_px\n0,1.0,nose,1,2\n0,1.0,nose,3,4\n", "p.csv:3:", "twice");
  expect("frame,t_s,id,x_px,y_px\n0,1.0,nose,1,2\n1,1.1,nose,3,4\n0,1.2,tail1,3,4\n", "p.csv:4:", "appears again");
  expect("frame,t_s,id,x_px,y_px\n0,1.0,nose,1,2\n0,1.05,tail1,3,4\n", "p.csv:3:", "differs");
  expect("frame,t_s,id,x_px,y_px\n0,1.0,nose,1,2\n1,0.5,nose,3,4\n", "p.csv:3:", "");
  expect("frame,t_s,id,x_px\n0,1.0,nose,1\n", "p.csv", "y_px");
  // Without a frame column, equal consecutive times form a frame; lost rows count as missing.
  const CylinderPointsFile f = ReadCylinderPoints(io::CsvTable::Parse(
      "t_s,id,x_px,y_px,status\n1.0,nose,1,2,ok\n1.0,tail1,3,4,lost\n1.0,tail2,5,6,ok\n2.0,nose,,,lost\n", "p.csv"));
  ASSERT_EQ(f.frames.size(), 2u);
  EXPECT_FALSE(f.frames[0].px[1].has_value());
  EXPECT_TRUE(f.frames[0].px[2].has_value());
}

// Issue 16 item 1: rk-attitude cylinder's options in one table, the solver's and the image fit's nested.
TEST(CylinderRunOptions, TableReachesNestedOptions) {
  CylinderRunOptions o;
  std::string why;
  EXPECT_TRUE(o.Check(&why)) << why;
  o.solve.max_edge_tilt_deg = 95.0;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why, "--max-edge-tilt-deg must be in (0, 90] deg");
  o = {};
  o.image_fit.initial_psf_sigma_px = 0.0;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_EQ(why, "--fit-psf-sigma must be in (0, 5] px");
  o = {};
  const auto* method = CylinderRunOptions::Table().Find("--method");
  ASSERT_NE(method, nullptr);
  EXPECT_TRUE(method->set_choice(&o, "search"));
  EXPECT_EQ(o.solve.method, CylinderMethod::kSearch);
  o.solve.max_edge_tilt_deg = 45.0;
  const io::Json j = o.ToJson();
  EXPECT_EQ(j.at("method"), "search");
  EXPECT_EQ(j.at("max_edge_tilt_deg"), 45.0);
  EXPECT_EQ(j.at("fit_max_iterations"), 30);
  EXPECT_EQ(j.at("angle_sigma_arcsec"), 0.0);
  EXPECT_EQ(j.at("theodolite_interp"), "cubic");
}

}  // namespace
}  // namespace rk::attitude
