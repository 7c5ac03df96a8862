// rk-sim pointing's trial folder (SPEC.md §6): a calibration session with truth.
//   trial.json            epoch_utc, station (WGS-84), turret; "sim" names the calibration inputs and truth
//   turret.csv            logged (quantised) turret angles t_s,az_deg,el_deg
//   points.csv            image points frame,t_s,id,x_px,y_px (rk-calibrate pointing --observations)
//   landmarks.csv         id,lat_deg,lon_deg,h_m,e_m,n_m,u_m (WGS-84 and station ENU)
//   stars.csv             id,ra_deg,dec_deg,pm_ra_mas_yr,pm_dec_mas_yr,parallax_mas,rv_kms (ICRS)
//   camera.json           the nominal camera the calibration starts from
//   truth/pointing.json   the true pointing model; truth/camera.json the true camera; truth/points.csv
//                         the noise-free image points
#pragma once

#include <string>

#include "io/json_util.h"
#include "sim/pointing_scenario.h"

namespace rk::sim {

struct PointingTrialSummary {
  std::size_t observations = 0, frames = 0, dwells = 0, landmarks = 0, stars = 0, turret_rows = 0;
  double duration_s = 0.0;
  io::Json ToJson() const;
};

// Writes the folder atomically (sim::TrialFolder); an existing non-empty `out_dir` is refused unless `force`.
PointingTrialSummary WritePointingTrial(const PointingSimOptions& options, const PointingSession& session,
                                        const std::string& out_dir, bool force);

}  // namespace rk::sim
